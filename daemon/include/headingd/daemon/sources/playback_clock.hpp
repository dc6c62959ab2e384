#pragma once
// The one clock the log file sources ([candump_log], [nmea_log]) play by, so that frames and
// sentences recorded together are played together: log time t (ns on the logs' own axis, the
// candump log's UNIX time and the NMEA UTC) is due at CLOCK_MONOTONIC
//   start_mono_ns + (t - log_t0_ns) / speed,
// where log_t0_ns is the earliest first timestamp of all the logs. The daemon fills
// log_t0_ns once the logs are read and start_mono_ns when it starts the sources; the sources
// only read it (after start(), from their own threads).
//
// With [playback] at_end = "loop" every log plays again and again, loop k later on the log
// axis by k * loop_ns: one loop is the logs' common span (earliest first to latest last
// timestamp) plus the shortest sample period among them, so that at the seam the IMU samples
// step on by one period and every log starts its next loop after it ended its last.
#include <cmath>
#include <cstdint>

namespace headingd::daemon {

struct PlaybackClock {
  double speed = 1.0;
  std::int64_t log_t0_ns = 0;
  std::int64_t start_mono_ns = 0;
  std::int64_t loop_ns = 0;  // the length of one loop on the log axis; 0 when not looping

  // CLOCK_MONOTONIC time at which log time `log_ns` is played.
  std::int64_t dueMonoNs(std::int64_t log_ns) const {
    return start_mono_ns + static_cast<std::int64_t>(std::llround(static_cast<double>(log_ns - log_t0_ns) / speed));
  }
  // The log time being played at CLOCK_MONOTONIC `mono_ns` (inverse of dueMonoNs).
  std::int64_t logNsAt(std::int64_t mono_ns) const {
    return log_t0_ns + static_cast<std::int64_t>(std::llround(static_cast<double>(mono_ns - start_mono_ns) * speed));
  }
};

}  // namespace headingd::daemon
