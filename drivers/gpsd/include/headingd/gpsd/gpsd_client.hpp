#pragma once
// A gpsd client on the caller's Boost.Asio io_context: connects to gpsd's JSON socket, asks
// for reports (?WATCH={"enable":true,"json":true};), reads TPV and SKY reports and calls back
// once per receiver epoch (GpsdEpochMerger) with an nmea::Fix, the same value the serial
// driver delivers.
//
// Survives what gpsd and the network do: gpsd not running yet, restarting (the connection
// closes, possibly mid-line), a peer sending garbage or endless lines. Each time it closes
// the socket, counts, and reconnects after a bounded back-off; nothing here blocks the
// io_context or spins. Bad lines are counted and handed to `on_problem` (the caller bounds
// how often it logs them).
//
// Threading: as SerialGpsReader: one thread runs the io_context; handlers and counters() on
// that thread; destroy it there or when the io_context is not running.
#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include "headingd/gpsd/gpsd_config.hpp"
#include "headingd/gpsd/gpsd_epoch_merger.hpp"
#include "headingd/gpsd/json_line_framer.hpp"
#include "headingd/live/epoch_idle_timer.hpp"
#include "headingd/live/reconnect_schedule.hpp"

namespace headingd::gpsd {

enum class GpsdState {
  kStopped,     // not started, or stopped
  kConnecting,  // resolving, connecting
  kConnected,   // watching
  kWaiting,     // gpsd unreachable or gone: reconnecting after the back-off
};
const char* gpsdStateName(GpsdState s);  // "stopped", "connecting", "connected", "waiting"

struct GpsdCounters {
  LineCounters lines;  // bytes, lines, oversized, cut (closed mid-line)
  std::uint64_t tpv_reports = 0;
  std::uint64_t sky_reports = 0;
  std::uint64_t other_reports = 0;   // VERSION, DEVICES, WATCH, ... (read and ignored)
  std::uint64_t malformed = 0;       // not JSON, no class, a field of the wrong type
  std::uint64_t missing_fields = 0;  // TPV without mode (not used), or a 2D/3D fix without lat/lon
  std::uint64_t epochs = 0;          // fixes delivered
  std::uint64_t late_reports = 0;    // TPVs of an epoch already delivered
  std::uint64_t connect_attempts = 0;
  std::uint64_t connect_failures = 0;
  std::uint64_t connects = 0;
  std::uint64_t disconnects = 0;  // gpsd closed the connection or a read failed
  GpsdState state = GpsdState::kStopped;
  std::string last_error;  // empty until something went wrong; kept after recovery
};

// Calls fn(name, value) for every counter, in a fixed order, with stable snake_case names
// (STATUS lists them so).
template <class Fn>
void forEachCounter(const GpsdCounters& c, Fn&& fn) {
  fn("epochs", c.epochs);
  fn("late_reports", c.late_reports);
  fn("bytes", c.lines.bytes);
  fn("lines", c.lines.lines);
  fn("oversized_lines", c.lines.oversized);
  fn("cut_lines", c.lines.cut);
  fn("tpv_reports", c.tpv_reports);
  fn("sky_reports", c.sky_reports);
  fn("other_reports", c.other_reports);
  fn("malformed", c.malformed);
  fn("missing_fields", c.missing_fields);
  fn("connect_attempts", c.connect_attempts);
  fn("connect_failures", c.connect_failures);
  fn("connects", c.connects);
  fn("disconnects", c.disconnects);
}

// A line that was not used: kind ("malformed", "missing_fields", "oversized", "cut") and what.
using ProblemHandler = std::function<void(std::string_view kind, const std::string& detail)>;

class GpsdClient {
 public:
  GpsdClient(boost::asio::io_context& io, GpsdConfig config, EpochHandler on_epoch, ProblemHandler on_problem = {});
  ~GpsdClient();
  GpsdClient(const GpsdClient&) = delete;
  GpsdClient& operator=(const GpsdClient&) = delete;

  // Connects (on the io_context, not in this call) and stays connected until stop().
  void start();
  // Closes the connection and cancels the retries; the epoch in progress is delivered.
  void stop();
  GpsdCounters counters() const;

  // The command that starts the reports.
  static constexpr std::string_view kWatchCommand = "?WATCH={\"enable\":true,\"json\":true};\n";

 private:
  void connect();
  void onConnected();
  void startRead();
  void onLine(std::string_view line, std::int64_t receive_ns);
  void lose(const std::string& why);
  void failConnect(const std::string& why);
  void closeSocket();
  void endStream();
  void setError(GpsdState state, const std::string& message);
  std::string where() const;

  GpsdConfig config_;
  ProblemHandler on_problem_;
  GpsdEpochMerger merger_;
  JsonLineFramer framer_;
  boost::asio::ip::tcp::resolver resolver_;
  boost::asio::ip::tcp::socket socket_;
  std::array<std::uint8_t, 4096> buffer_{};
  GpsdCounters counters_;
  live::EpochIdleTimer epoch_idle_;
  // Running or not, the next connect, the back-off. Last, so that its guard, which every
  // handler holds, expires first: once the client is gone, they do nothing.
  live::ReconnectSchedule reconnect_;
};

}  // namespace headingd::gpsd
