#pragma once
// When each frame of a log is played, so that one bad timestamp can neither hold playback
// back nor push it ahead (a candump log's time is the recorder's wall clock: a frame stamped
// (0.000000) or a year ahead would otherwise be waited for, for ever). Frames stay in file
// order; on the log's own time axis:
//  - outliers are skipped: a run of at most kMaxOutlierRun frames more than kJumpNs away from
//    the frames on both sides of it, which agree with each other (within kJumpNs); at the
//    start or end of the log, a run that the rest of the log would reach only by a time step
//    (below), the frames after (before) it agreeing with each other;
//  - a time step, a step between two played frames backwards by more than kJumpNs or forwards
//    by more than kLongestGapNs, is played at once: the frames after it keep their spacing
//    from there on;
//  - a shorter step backwards (frames of two epochs swapped) is played at once, a shorter
//    step forwards (a gap in the log) is waited for, so the log stays on the clock it shares
//    with the NMEA log.
// Pure: no clock, no I/O.
#include <cstdint>
#include <span>
#include <vector>

namespace headingd::daemon {

struct LogFrameTimes {
  static constexpr std::int64_t kJumpNs = 1'000'000'000;         // 1 s
  static constexpr std::int64_t kLongestGapNs = 60'000'000'000;  // 60 s
  static constexpr std::size_t kMaxOutlierRun = 16;              // frames

  std::vector<bool> skipped;              // per frame of the input: an outlier, not played
  std::vector<std::int64_t> play_ns;      // per frame: its time on the playback axis (unused if skipped)
  std::uint64_t outlier_frames = 0;       // frames skipped
  std::uint64_t time_steps = 0;           // steps played at once
  std::int64_t first_outlier_index = -1;  // index of the first skipped frame, -1 if none
  std::int64_t first_step_index = -1;     // index of the frame after the first time step, -1 if none
};

// `log_ns`: each frame's logged time, in file order.
LogFrameTimes placeLogFrames(std::span<const std::int64_t> log_ns);

}  // namespace headingd::daemon
