#include "headingd/live/epoch_idle_timer.hpp"

#include <utility>

#include "headingd/live/clocks.hpp"

namespace headingd::live {

EpochIdleTimer::EpochIdleTimer(boost::asio::io_context& io, double idle_s, std::function<bool()> epoch_pending,
                               std::function<void()> end_epoch)
    : timer_(io), idle_s_(idle_s), epoch_pending_(std::move(epoch_pending)), end_epoch_(std::move(end_epoch)) {}

void EpochIdleTimer::fed(std::int64_t receive_ns) {
  last_receive_ns_ = receive_ns;
  if (idle_s_ <= 0.0 || armed_ || !epoch_pending_()) return;
  waitFor(secondsToNs(idle_s_));
}

void EpochIdleTimer::waitFor(std::chrono::nanoseconds wait) {
  armed_ = true;
  timer_.expires_after(wait);
  timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired()) return;
    armed_ = false;
    if (!ec) onTimer();
  });
}

void EpochIdleTimer::onTimer() {
  const auto quiet_for = std::chrono::nanoseconds(monotonicNs() - last_receive_ns_);
  const auto idle = secondsToNs(idle_s_);
  if (quiet_for >= idle) {
    end_epoch_();
    return;
  }
  waitFor(idle - quiet_for);
}

}  // namespace headingd::live
