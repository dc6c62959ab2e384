#pragma once
// An NMEA log played at the pace the receiver sent it, for the daemon's file mode and for
// tests: the same EpochAssembler, the same handlers and the same Fix values as the serial
// driver, with the log's sentences standing in for the port.
//
// Pacing: the log is cut into groups, one per UTC time of day (a group starts at each
// sentence whose time differs from the group's; lines without a time, such as VTG and GSA,
// go with the group before them). Group k is fed at start + sum of the time steps between
// consecutive groups, divided by the speed factor, on absolute steady_timer deadlines (no
// drift, no sleeping thread). A step that goes backwards (receiver reset) plays at once;
// one longer than max_gap_s (a gap in the log) plays as max_gap_s; midnight wraps.
// The epoch of a group is delivered as soon as its group has been fed: all its lines are in.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "headingd/nmea/serial_epoch_assembler.hpp"

namespace headingd::nmea {

struct NmeaLogPlayerConfig {
  std::string path;        // plain text NMEA; '#' comment lines (gpsd captures) are skipped
  double speed = 1.0;      // 1: real time; 10: ten times faster (tests)
  double max_gap_s = 5.0;  // longest wait between two groups, in log time
  ParserConfig parser;
  // The log's text when the caller has read it already (decompressed, say); `path` then only
  // names it in messages. Without it the file at `path` is read as it is.
  std::optional<std::string> contents = std::nullopt;
};

struct NmeaLogPlayerCounters {
  Counters parser;
  EpochCounters epochs;
  std::uint64_t comment_lines = 0;
  std::uint64_t groups_total = 0;
  std::uint64_t groups_played = 0;
  std::uint64_t long_gaps = 0;       // steps longer than max_gap_s, shortened
  std::uint64_t backward_steps = 0;  // time of day went back (not a midnight)
  bool finished = false;
};

class NmeaLogPlayer {
 public:
  using FinishedHandler = std::function<void()>;

  // Reads and indexes the whole file; throws std::runtime_error naming the file if it cannot
  // be read, and std::invalid_argument for a speed or max_gap_s that is not positive.
  NmeaLogPlayer(boost::asio::io_context& io, NmeaLogPlayerConfig config, FixHandler on_fix, LineHandler on_line = {},
                FinishedHandler on_finished = {});
  ~NmeaLogPlayer();
  NmeaLogPlayer(const NmeaLogPlayer&) = delete;
  NmeaLogPlayer& operator=(const NmeaLogPlayer&) = delete;

  // Plays from the first group; the first is fed on the io_context right away. Once the log
  // has been played (on_finished called), start() plays it again (a looping player).
  void start();
  // Stops after the group being fed; the epoch in progress is delivered.
  void stop();

  NmeaLogPlayerCounters counters() const;

 private:
  struct Group {
    std::size_t begin = 0;  // byte range in bytes_
    std::size_t end = 0;
    std::chrono::nanoseconds delay{0};  // after the previous group, already divided by speed
  };

  void index();
  void scheduleNext();
  void playGroup();

  NmeaLogPlayerConfig config_;
  EpochAssembler assembler_;
  FinishedHandler on_finished_;
  boost::asio::steady_timer timer_;
  std::vector<std::uint8_t> bytes_;  // the log without comment lines
  std::vector<Group> groups_;
  std::size_t next_group_ = 0;
  std::chrono::steady_clock::time_point next_due_;
  bool running_ = false;
  NmeaLogPlayerCounters counters_;
  std::shared_ptr<int> alive_ = std::make_shared<int>(0);
};

}  // namespace headingd::nmea
