#include "headingd/daemon/sources/log_frame_times.hpp"

namespace headingd::daemon {
namespace {

using L = LogFrameTimes;

// |a - b| > kJumpNs without overflow for any two int64 times.
bool far(std::int64_t a, std::int64_t b) {
  const std::uint64_t d = a > b ? static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b)
                                : static_cast<std::uint64_t>(b) - static_cast<std::uint64_t>(a);
  return d > static_cast<std::uint64_t>(L::kJumpNs);
}

// A step from `from` to `to` that playback does not wait for: backwards by more than kJumpNs,
// forwards by more than kLongestGapNs.
bool isTimeStep(std::int64_t from, std::int64_t to) {
  if (to < from) return far(from, to);
  const std::uint64_t d = static_cast<std::uint64_t>(to) - static_cast<std::uint64_t>(from);
  return d > static_cast<std::uint64_t>(L::kLongestGapNs);
}

void skipRange(L& out, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    out.skipped[i] = true;
    ++out.outlier_frames;
  }
  if (begin < end && (out.first_outlier_index < 0 || static_cast<std::int64_t>(begin) < out.first_outlier_index)) {
    out.first_outlier_index = static_cast<std::int64_t>(begin);
  }
}

}  // namespace

LogFrameTimes placeLogFrames(std::span<const std::int64_t> t) {
  const std::size_t n = t.size();
  LogFrameTimes out;
  out.skipped.assign(n, false);
  out.play_ns.assign(t.begin(), t.end());
  if (n < 3) return out;  // too few frames to tell which ones are out of place

  // A run at the start: the first k frames, then a time step into frames that agree.
  std::size_t first = 0;
  // The run's own frames agree with each other (else the jump inside it is handled below).
  for (std::size_t k = 1; k <= L::kMaxOutlierRun && k + 1 < n; ++k) {
    if (isTimeStep(t[k - 1], t[k]) && !far(t[k], t[k + 1])) {
      skipRange(out, 0, k);
      first = k;
      break;
    }
    if (far(t[k - 1], t[k])) break;
  }

  // Runs inside the log and at its end, against the last frame kept.
  std::size_t last_kept = first;
  for (std::size_t i = first + 1; i < n;) {
    if (!far(t[i], t[last_kept])) {
      last_kept = i++;
      continue;
    }
    std::size_t back = 0;  // first frame after the run that agrees with the frame before it
    for (std::size_t k = 1; k <= L::kMaxOutlierRun && i + k < n; ++k) {
      if (!far(t[i + k], t[last_kept])) {
        back = i + k;
        break;
      }
    }
    if (back != 0) {
      skipRange(out, i, back);
      i = back;
      continue;
    }
    const bool agreed_before = last_kept > first && !far(t[last_kept - 1], t[last_kept]);
    if (n - i <= L::kMaxOutlierRun && agreed_before && isTimeStep(t[last_kept], t[i])) {
      skipRange(out, i, n);
      break;
    }
    last_kept = i++;  // a gap or a slow log: played as it is
  }

  // The playback axis over the frames kept: time steps are played at once.
  std::int64_t shift = 0;
  bool have_previous = false;
  std::size_t previous = 0;
  for (std::size_t i = first; i < n; ++i) {
    if (out.skipped[i]) continue;
    if (have_previous && isTimeStep(t[previous], t[i])) {
      ++out.time_steps;
      if (out.first_step_index < 0) out.first_step_index = static_cast<std::int64_t>(i);
      shift = out.play_ns[previous] - t[i];
    }
    out.play_ns[i] = t[i] + shift;
    have_previous = true;
    previous = i;
  }
  return out;
}

}  // namespace headingd::daemon
