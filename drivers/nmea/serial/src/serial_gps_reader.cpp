#include "headingd/nmea/serial_gps_reader.hpp"

#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <utility>
#include <variant>

#include <spdlog/spdlog.h>
#include <boost/asio/error.hpp>

#include "headingd/nmea/serial_port_open.hpp"

namespace headingd::nmea {
namespace {

std::int64_t monotonicNowNs() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::chrono::nanoseconds toNs(double seconds) {
  return std::chrono::nanoseconds(static_cast<std::int64_t>(seconds * 1e9));
}

}  // namespace

const char* serialGpsStateName(SerialGpsState s) {
  switch (s) {
    case SerialGpsState::kStopped: return "stopped";
    case SerialGpsState::kOpen: return "open";
    case SerialGpsState::kWaitingForDevice: return "waiting_for_device";
    case SerialGpsState::kError: return "error";
    case SerialGpsState::kBusy: return "busy";
  }
  return "?";
}

SerialGpsReader::SerialGpsReader(boost::asio::io_context& io, SerialGpsConfig config, FixHandler on_fix,
                                 LineHandler on_line)
    : config_(std::move(config)),
      assembler_(config_.parser, std::move(on_fix), std::move(on_line)),
      port_(io),
      reopen_timer_(io),
      idle_timer_(io),
      path_timer_(io),
      backoff_(config_.reopen_backoff_initial_s, config_.reopen_backoff_max_s) {}

SerialGpsReader::~SerialGpsReader() {
  alive_.reset();
  closePort();
}

void SerialGpsReader::start() {
  if (running_) return;
  running_ = true;
  backoff_.reset();
  scheduleOpen(std::chrono::nanoseconds(0));
}

void SerialGpsReader::stop() {
  if (!running_) return;
  running_ = false;
  reopen_timer_.cancel();
  closePort();
  endStream();
  counters_.state = SerialGpsState::kStopped;
}

SerialGpsCounters SerialGpsReader::counters() const {
  SerialGpsCounters c = counters_;
  c.parser = assembler_.parserCounters();
  c.epochs = assembler_.epochCounters();
  return c;
}

void SerialGpsReader::scheduleOpen(std::chrono::nanoseconds delay) {
  reopen_timer_.expires_after(delay);
  reopen_timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired() || ec || !running_) return;
    attemptOpen();
  });
}

void SerialGpsReader::setError(SerialGpsState state, const std::string& message) {
  // Logged when it changes, so a device that stays away is reported once, not per retry.
  if (message != counters_.last_error || state != counters_.state) {
    spdlog::warn("gps: {}", message);
  }
  counters_.state = state;
  counters_.last_error = message;
}

void SerialGpsReader::attemptOpen() {
  if (counters_.open_attempts > 0) ++counters_.reopen_attempts;
  ++counters_.open_attempts;
  auto result = openSerialDevice(config_.device, config_.baud);
  if (auto* failed = std::get_if<SerialOpenFailure>(&result)) {
    if (failed->busy) {
      ++counters_.port_busy;
      setError(SerialGpsState::kBusy, failed->message + "; retrying");
    } else {
      setError(failed->device_missing ? SerialGpsState::kWaitingForDevice : SerialGpsState::kError, failed->message);
    }
    scheduleOpen(backoff_.afterFailure());
    return;
  }
  const int fd = std::get<OpenedSerialDevice>(result).fd;
  struct stat st {};
  open_dev_ = ::fstat(fd, &st) == 0 ? static_cast<std::uint64_t>(st.st_rdev) : 0;
  boost::system::error_code ec;
  port_.assign(fd, ec);
  if (ec) {
    releaseSerialDevice(fd);
    ::close(fd);
    setError(SerialGpsState::kError, config_.device + ": " + ec.message());
    scheduleOpen(backoff_.afterFailure());
    return;
  }
  if (ever_opened_) ++counters_.reopens;
  ever_opened_ = true;
  counters_.state = SerialGpsState::kOpen;
  backoff_.reset();
  spdlog::info("gps: {} open at {} baud", config_.device, config_.baud);
  startRead();
  startPathCheck();
}

void SerialGpsReader::startRead() {
  port_.async_read_some(boost::asio::buffer(buffer_),
                        [this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec, std::size_t n) {
                          if (alive.expired() || ec == boost::asio::error::operation_aborted) return;
                          onRead(ec, n);
                        });
}

void SerialGpsReader::onRead(const boost::system::error_code& ec, std::size_t n) {
  if (!port_.is_open()) return;  // closed after this read completed
  if (n > 0) {
    last_receive_ns_ = monotonicNowNs();
    ++counters_.reads;
    const std::span<const std::uint8_t> bytes(buffer_.data(), n);
    if (tap_ != nullptr) tap_->fed(bytes, last_receive_ns_);
    assembler_.feed(bytes, last_receive_ns_);
    armIdleTimer();
  }
  if (ec) {
    // EOF: the other end hung up (a pty master closed). EIO: the USB device is gone.
    if (ec != boost::asio::error::eof) ++counters_.read_errors;
    lose("read failed: " + ec.message());
    return;
  }
  startRead();
}

void SerialGpsReader::armIdleTimer() {
  if (config_.epoch_idle_s <= 0.0 || idle_timer_armed_ || !assembler_.epochPending()) return;
  idle_timer_armed_ = true;
  idle_timer_.expires_after(toNs(config_.epoch_idle_s));
  idle_timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired()) return;
    idle_timer_armed_ = false;
    if (!ec) onIdleTimer();
  });
}

void SerialGpsReader::onIdleTimer() {
  // One timer per quiet period: bytes since it was armed push the deadline instead of
  // re-arming it on every read.
  const auto quiet_for = std::chrono::nanoseconds(monotonicNowNs() - last_receive_ns_);
  const auto idle = toNs(config_.epoch_idle_s);
  if (quiet_for >= idle) {
    if (tap_ != nullptr && assembler_.epochPending()) tap_->epochCompleted(monotonicNowNs());
    assembler_.completeEpoch();
    return;
  }
  idle_timer_armed_ = true;
  idle_timer_.expires_after(idle - quiet_for);
  idle_timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired()) return;
    idle_timer_armed_ = false;
    if (!ec) onIdleTimer();
  });
}

void SerialGpsReader::startPathCheck() {
  if (config_.path_check_s <= 0.0) return;
  path_timer_.expires_after(toNs(config_.path_check_s));
  path_timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired() || ec || !port_.is_open()) return;
    onPathCheck();
  });
}

void SerialGpsReader::onPathCheck() {
  // A USB receiver unplugged does not always fail the read at once (some adapters just go
  // quiet), and a udev symlink may be re-pointed while the old device lingers.
  struct stat st {};
  if (::stat(config_.device.c_str(), &st) != 0) {
    lose("device path disappeared");
    return;
  }
  if (static_cast<std::uint64_t>(st.st_rdev) != open_dev_) {
    lose("device path now names another device");
    return;
  }
  startPathCheck();
}

void SerialGpsReader::lose(const std::string& why) {
  ++counters_.disconnects;
  closePort();
  endStream();
  setError(SerialGpsState::kWaitingForDevice, config_.device + ": " + why + "; reopening");
  scheduleOpen(backoff_.reset());
}

void SerialGpsReader::endStream() {
  if (tap_ != nullptr) tap_->streamEnded(monotonicNowNs());
  assembler_.endOfStream();
}

void SerialGpsReader::closePort() {
  idle_timer_.cancel();
  path_timer_.cancel();
  boost::system::error_code ignored;
  if (port_.is_open()) releaseSerialDevice(port_.native_handle());
  port_.close(ignored);
}

}  // namespace headingd::nmea
