#pragma once
// The serial GPS driver: reads a receiver's NMEA stream from a serial port on the caller's
// Boost.Asio io_context and calls back once per completed fix epoch.
//
// Survives what a body-worn USB receiver does: not plugged in at start, unplugged (read
// gives EOF or EIO, or the path vanishes or is re-pointed to another device), plugged back
// in. Each time it closes the port and retries the path with a bounded back-off
// (SerialGpsConfig); nothing here blocks the io_context or spins.
//
// The port is ours alone (serial_port_open.hpp): while another program holds it (gpsd, a
// terminal program, a second headingd) the reader reads nothing, says who holds it (state
// busy, last_error "…: busy, held by gpsd (pid 812); retrying", counter port_busy) and
// retries with the same back-off, rather than take part of the byte stream.
//
// Threading: everything runs on the io_context's thread(s) through one implicit strand, so
// run the io_context on one thread. Handlers are called on that thread; counters() too must
// be called there (post to it from elsewhere). Destroy the reader on that thread or when the
// io_context is not running; pending operations then finish as no-ops.
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include <boost/asio/io_context.hpp>
#include <boost/asio/serial_port.hpp>
#include <boost/asio/steady_timer.hpp>

#include "headingd/live/epoch_idle_timer.hpp"
#include "headingd/live/reconnect_schedule.hpp"
#include "headingd/nmea/counters.hpp"
#include "headingd/nmea/serial_epoch_assembler.hpp"
#include "headingd/nmea/serial_gps_config.hpp"

namespace headingd::nmea {

enum class SerialGpsState {
  kStopped,           // not started, or stopped
  kOpen,              // reading
  kWaitingForDevice,  // the path does not exist (not plugged in, or unplugged): retrying
  kError,             // the path exists but cannot be used (not a tty, permissions): retrying
  kBusy,              // another program holds the port: retrying
};
// "stopped", "open", "waiting_for_device", "error", "busy"
const char* serialGpsStateName(SerialGpsState s);

struct SerialGpsCounters {
  Counters parser;                // bytes, lines, and every sentence outcome (counters.hpp)
  EpochCounters epochs;           // fixes delivered, late sentences
  std::uint64_t reads = 0;        // completed reads with data
  std::uint64_t read_errors = 0;  // reads that failed with an error other than end of file
  std::uint64_t disconnects = 0;  // the open device went away (EOF, read error, path changed)
  std::uint64_t open_attempts = 0;
  std::uint64_t reopen_attempts = 0;  // attempts after the first one
  std::uint64_t reopens = 0;          // successful opens after the first one
  std::uint64_t port_busy = 0;        // open attempts that found the port held by another program
  SerialGpsState state = SerialGpsState::kStopped;
  std::string last_error;  // empty until something went wrong; kept after recovery
};

// Calls fn(name, value) for the reader's own counters, in a fixed order, with stable
// snake_case names; the parser's are nmea::forEachCounter(c.parser, ...).
template <class Fn>
void forEachCounter(const SerialGpsCounters& c, Fn&& fn) {
  fn("epochs", c.epochs.epochs);
  fn("reads", c.reads);
  fn("read_errors", c.read_errors);
  fn("disconnects", c.disconnects);
  fn("open_attempts", c.open_attempts);
  fn("reopens", c.reopens);
  fn("port_busy", c.port_busy);
}

class SerialGpsReader {
 public:
  SerialGpsReader(boost::asio::io_context& io, SerialGpsConfig config, FixHandler on_fix, LineHandler on_line = {});
  ~SerialGpsReader();
  SerialGpsReader(const SerialGpsReader&) = delete;
  SerialGpsReader& operator=(const SerialGpsReader&) = delete;

  // Opens the device (on the io_context, not in this call) and keeps it open until stop().
  void start();
  // Closes the device and cancels the retries; the epoch in progress is delivered.
  void stop();

  SerialGpsCounters counters() const;
  // Everything given to the epoch assembler from now on also goes to `tap` (null: none), on
  // the io_context's thread. Set before start().
  void setInputTap(AssemblerInputTap* tap) { tap_ = tap; }
  const SerialGpsConfig& config() const { return config_; }

 private:
  void attemptOpen();
  void startRead();
  void onRead(const boost::system::error_code& ec, std::size_t n);
  void endQuietEpoch();  // the epoch_idle_s timer ended the epoch in progress
  void startPathCheck();
  void onPathCheck();
  void lose(const std::string& why);
  void closePort();
  void endStream();  // the assembler's endOfStream(), through the tap
  void setError(SerialGpsState state, const std::string& message);

  SerialGpsConfig config_;
  EpochAssembler assembler_;
  boost::asio::serial_port port_;
  boost::asio::steady_timer path_timer_;
  std::array<std::uint8_t, 512> buffer_{};
  bool ever_opened_ = false;
  std::uint64_t open_dev_ = 0;  // st_rdev of the open device, to notice a re-pointed path
  SerialGpsCounters counters_;
  AssemblerInputTap* tap_ = nullptr;
  live::EpochIdleTimer epoch_idle_;
  // Running or not, the next open, the back-off. Last, so that its guard, which every
  // handler holds, expires first: once the reader is gone, they do nothing.
  live::ReconnectSchedule reopen_;
};

}  // namespace headingd::nmea
