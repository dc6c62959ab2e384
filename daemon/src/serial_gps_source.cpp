#include "headingd/daemon/serial_gps_source.hpp"

#include <boost/asio/post.hpp>
#include <future>

#include "headingd/nmea/gps_observation_from_fix.hpp"

namespace headingd::daemon {
namespace {
// How often the reader's counters are copied for STATUS (they may only be read on its thread).
constexpr auto kSnapshotPeriod = std::chrono::milliseconds(250);
}  // namespace

SerialGpsSource::SerialGpsSource(std::string name, const nmea::SerialGpsConfig& config, std::uint16_t source_index,
                                 SampleRing<GpsRingEntry>* gps_ring)
    : name_(std::move(name)), source_index_(source_index), ring_(gps_ring), snapshot_timer_(io_) {
  reader_ = std::make_unique<nmea::SerialGpsReader>(
      io_, config, [this](const nmea::Fix& fix, std::int64_t receive_ns) { onFix(fix, receive_ns); });
}

SerialGpsSource::~SerialGpsSource() { stop(); }

void SerialGpsSource::onFix(const nmea::Fix& fix, std::int64_t receive_ns) {
  GpsRingEntry e;
  e.observation = nmea::gpsObservationFromFix(fix, receive_ns);
  e.arrival_mono_ns = receive_ns;
  e.source_index = source_index_;
  (ring_->push(e) ? pushed_ : dropped_).fetch_add(1, std::memory_order_relaxed);
}

void SerialGpsSource::snapshotCounters() {
  {
    std::lock_guard lock(snapshot_mutex_);
    snapshot_ = reader_->counters();
  }
  snapshot_timer_.expires_after(kSnapshotPeriod);
  snapshot_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) snapshotCounters();
  });
}

void SerialGpsSource::start() {
  work_.emplace(io_.get_executor());
  boost::asio::post(io_, [this] {
    reader_->start();
    snapshotCounters();
  });
  thread_ = std::thread([this] { io_.run(); });
}

void SerialGpsSource::stop() {
  if (!thread_.joinable()) return;
  // The reader is stopped on its own thread, then the io_context runs out of work.
  std::promise<void> stopped;
  boost::asio::post(io_, [this, &stopped] {
    reader_->stop();
    snapshot_timer_.cancel();
    snapshot_ = reader_->counters();
    stopped.set_value();
  });
  stopped.get_future().wait_for(std::chrono::milliseconds(500));
  work_.reset();
  io_.stop();
  thread_.join();
}

void SerialGpsSource::report(SourceReport& out) const {
  std::lock_guard lock(snapshot_mutex_);
  const nmea::SerialGpsCounters& c = snapshot_;
  switch (c.state) {
    case nmea::SerialGpsState::kOpen: out.state = SourceState::kRunning; break;
    case nmea::SerialGpsState::kWaitingForDevice: out.state = SourceState::kWaiting; break;
    case nmea::SerialGpsState::kBusy: out.state = SourceState::kWaiting; break;  // last_error names the holder
    case nmea::SerialGpsState::kError: out.state = SourceState::kError; break;
    case nmea::SerialGpsState::kStopped: out.state = SourceState::kStarting; break;
  }
  if (out.last_error != c.last_error) out.last_error = c.last_error;
  std::size_t i = 0;
  out.set(i++, "epochs_pushed", pushed_.load(std::memory_order_relaxed));
  out.set(i++, "ring_full_drops", dropped_.load(std::memory_order_relaxed));
  out.set(i++, "epochs", c.epochs.epochs);
  out.set(i++, "reads", c.reads);
  out.set(i++, "read_errors", c.read_errors);
  out.set(i++, "disconnects", c.disconnects);
  out.set(i++, "open_attempts", c.open_attempts);
  out.set(i++, "reopens", c.reopens);
  out.set(i++, "port_busy", c.port_busy);
  nmea::forEachCounter(c.parser, [&](const char* name, std::uint64_t v) { out.set(i++, "nmea_", name, v); });
}

}  // namespace headingd::daemon
