#include "headingd/nmea/serial_gps_reader.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <utility>
#include <variant>

#include <spdlog/spdlog.h>
#include <boost/asio/error.hpp>

#include "headingd/live/clocks.hpp"
#include "headingd/live/link_error.hpp"
#include "headingd/nmea/serial_port_open.hpp"

namespace headingd::nmea {

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
      path_timer_(io),
      epoch_idle_(
          io, config_.epoch_idle_s, [this] { return assembler_.epochPending(); }, [this] { endQuietEpoch(); }),
      reopen_(io, {config_.reopen_backoff_initial_s, config_.reopen_backoff_max_s}, [this] { attemptOpen(); }) {}

SerialGpsReader::~SerialGpsReader() { closePort(); }

void SerialGpsReader::start() { reopen_.start(); }

void SerialGpsReader::stop() {
  if (!reopen_.stop()) return;
  closePort();
  endStream();
  counters_.state = SerialGpsState::kStopped;
}

void SerialGpsReader::setError(SerialGpsState state, const std::string& message) {
  live::setLinkError(counters_.state, counters_.last_error, state, message, "gps");
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
    reopen_.retryAfterFailure();
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
    reopen_.retryAfterFailure();
    return;
  }
  if (ever_opened_) ++counters_.reopens;
  ever_opened_ = true;
  counters_.state = SerialGpsState::kOpen;
  reopen_.succeeded();
  spdlog::info("gps: {} open at {} baud", config_.device, config_.baud);
  startRead();
  startPathCheck();
}

void SerialGpsReader::startRead() {
  port_.async_read_some(boost::asio::buffer(buffer_),
                        [this, alive = reopen_.guard()](const boost::system::error_code& ec, std::size_t n) {
                          if (alive.expired() || ec == boost::asio::error::operation_aborted) return;
                          onRead(ec, n);
                        });
}

void SerialGpsReader::onRead(const boost::system::error_code& ec, std::size_t n) {
  if (!port_.is_open()) return;  // closed after this read completed
  if (n > 0) {
    const std::int64_t receive_ns = live::monotonicNs();
    ++counters_.reads;
    const std::span<const std::uint8_t> bytes(buffer_.data(), n);
    if (tap_ != nullptr) tap_->fed(bytes, receive_ns);
    assembler_.feed(bytes, receive_ns);
    epoch_idle_.fed(receive_ns);
  }
  if (ec) {
    // EOF: the other end hung up (a pty master closed). EIO: the USB device is gone.
    if (ec != boost::asio::error::eof) ++counters_.read_errors;
    lose("read failed: " + ec.message());
    return;
  }
  startRead();
}

void SerialGpsReader::endQuietEpoch() {
  if (tap_ != nullptr && assembler_.epochPending()) tap_->epochCompleted(live::monotonicNs());
  assembler_.completeEpoch();
}

void SerialGpsReader::startPathCheck() {
  if (config_.path_check_s <= 0.0) return;
  path_timer_.expires_after(live::secondsToNs(config_.path_check_s));
  path_timer_.async_wait([this, alive = reopen_.guard()](const boost::system::error_code& ec) {
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
  reopen_.retryAfterLoss();
}

void SerialGpsReader::endStream() {
  if (tap_ != nullptr) tap_->streamEnded(live::monotonicNs());
  assembler_.endOfStream();
}

void SerialGpsReader::closePort() {
  epoch_idle_.cancel();
  path_timer_.cancel();
  boost::system::error_code ignored;
  if (port_.is_open()) releaseSerialDevice(port_.native_handle());
  port_.close(ignored);
}

SerialGpsCounters SerialGpsReader::counters() const {
  SerialGpsCounters c = counters_;
  c.parser = assembler_.parserCounters();
  c.epochs = assembler_.epochCounters();
  return c;
}

}  // namespace headingd::nmea
