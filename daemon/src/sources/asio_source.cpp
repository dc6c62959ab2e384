#include "headingd/daemon/sources/asio_source.hpp"

#include <boost/asio/post.hpp>
#include <future>

namespace headingd::daemon {

AsioSourceBase::AsioSourceBase(std::string name, std::uint16_t source_index, Lifetime lifetime,
                               std::chrono::milliseconds snapshot_period)
    : name_(std::move(name)),
      source_index_(source_index),
      lifetime_(lifetime),
      snapshot_period_(snapshot_period),
      tick_timer_(io_) {}

void AsioSourceBase::start() {
  if (thread_.joinable()) return;
  if (lifetime_ == Lifetime::kUntilStopped) work_.emplace(io_.get_executor());
  boost::asio::post(io_, [this] {
    onStart();
    if (snapshot_period_.count() > 0) {
      ticking_ = true;
      tick();
    }
  });
  thread_ = std::thread([this] {
    runThreadStartHook();
    io_.run();
  });
}

void AsioSourceBase::tick() {
  onTick();
  takeSnapshot();
  tick_timer_.expires_after(snapshot_period_);
  tick_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec && ticking_) tick();
  });
}

void AsioSourceBase::stopTicks() {
  ticking_ = false;
  tick_timer_.cancel();
}

void AsioSourceBase::stop() {
  if (!thread_.joinable()) return;
  if (lifetime_ == Lifetime::kUntilStopped) {
    // The driver is stopped on its own thread, then the io_context runs out of work.
    std::promise<void> stopped;
    boost::asio::post(io_, [this, &stopped] {
      onStop();
      stopTicks();
      stopped.set_value();
    });
    stopped.get_future().wait_for(std::chrono::milliseconds(500));
    work_.reset();
  }
  io_.stop();
  thread_.join();
}

}  // namespace headingd::daemon
