#pragma once
// When a CAN source's periodic flush gives up on an open IMU epoch (releases it, or counts it
// incomplete).
//
// Without sequence counters the epoch window is what groups frames into an epoch, so the flush
// must use exactly that window ([can] epoch_window_s). With counters the next counter value
// closes an epoch as soon as its first frame arrives; the flush then only matters when no
// further frame comes (the last epoch before the bus goes quiet, or a lost frame), and giving
// up early only does harm: under load (measured under plain QEMU emulation) the frames of one
// epoch arrive milliseconds apart, and an epoch flushed after 2 ms was split into an
// incomplete epoch and "late" frames, and stalls of the receiving thread of 0.25-0.35 s were
// measured there (frames wait in the socket while the flush timer sees the wall clock move).
// So with counters the flush waits at least kCountedEpochFlushAgeNs, which costs latency only
// when frames are lost.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "headingd/can/can_config.hpp"
#include "headingd/can/epoch_assembler.hpp"
#include "headingd/can/imu_frame_codec.hpp"

namespace headingd::can {

inline constexpr std::int64_t kCountedEpochFlushAgeNs = 500'000'000;  // 0.5 s: 50 periods of a 100 Hz IMU

inline std::int64_t epochFlushAgeNs(const CanConfig& config, const ImuFrameCodec& codec) {
  const auto window_ns = static_cast<std::int64_t>(std::llround(config.epoch_window_s * 1e9));
  return codec.sequenceBits() == 0 ? window_ns : std::max(window_ns, kCountedEpochFlushAgeNs);
}

// EpochAssembler::flush(now) gives up after the configured window; moving `now` back by the
// difference makes it give up after `flush_age_ns` instead.
inline AssembledSamples flushEpoch(EpochAssembler& assembler, const CanConfig& config, std::int64_t flush_age_ns,
                                   std::int64_t now_ns) {
  const auto window_ns = static_cast<std::int64_t>(std::llround(config.epoch_window_s * 1e9));
  return assembler.flush(now_ns - (flush_age_ns - window_ns));
}

}  // namespace headingd::can
