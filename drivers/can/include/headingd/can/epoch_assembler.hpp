#pragma once
// Frames -> ImuSample. The gyro, accelerometer and magnetometer frames of one epoch (one
// sampling instant of the IMU) are collected and released as one sample:
//  - an epoch is recognised by its counter (`sequence` signals) or, without counters, by
//    arrival within `epoch_window_s` of its first frame with no axis repeated;
//  - a sample needs all gyro and accelerometer axes; an epoch that ends without them is
//    counted as incomplete, never invented;
//  - a magnetometer slower than the gyro is normal: samples without a fresh magnetometer
//    frame have has_mag = false. With epoch_waits_for_mag, an epoch is released as soon as
//    gyro, accel and mag are all there, otherwise when the next epoch starts (or flush()
//    finds it older than the window); without it, as soon as gyro and accel are there, and a
//    magnetometer frame arriving after that goes with the next sample;
//  - t_ns is the kernel timestamp of the epoch's first frame (the closest to the instant
//    the IMU sampled); the daemon maps it to its monotonic clock.
// No allocation per frame; the caller owns threading (one assembler per receiving thread).
#include <array>
#include <cstdint>

#include "headingd/can/imu_frame_codec.hpp"
#include "headingd/core/imu_sample.hpp"

namespace headingd::can {

struct EpochSettings {
  std::int64_t window_ns = 2'000'000;
  bool wait_for_mag = true;
};
EpochSettings epochSettingsFrom(const CanConfig& config);

struct AssemblerCounters {
  std::uint64_t frames = 0;          // every frame pushed
  std::uint64_t decoded_frames = 0;  // frames of a mapped message with the right length
  std::uint64_t samples = 0;         // samples released
  std::uint64_t samples_with_mag = 0;
  std::uint64_t incomplete_epochs = 0;    // epochs that ended without all gyro and accel axes
  std::uint64_t sequence_gaps = 0;        // times the epoch counter skipped
  std::uint64_t missing_epochs = 0;       // epochs the counter skipped over, in total (less those that came late)
  std::uint64_t reordered_epochs = 0;     // epochs whose counter is behind a newer one's (arrived late)
  std::uint64_t duplicate_frames = 0;     // a message repeated within one counted epoch
  std::uint64_t late_frames = 0;          // gyro/accel frames of an epoch already released
  std::uint64_t late_mag_frames = 0;      // magnetometer frames after their epoch: used for the next sample
  std::uint64_t superseded_mag = 0;       // such a magnetometer value replaced by a newer one before use
  std::uint64_t unknown_id_frames = 0;    // id not among the mapped messages
  std::uint64_t wrong_length_frames = 0;  // mapped id, length differs from the DBC
  std::uint64_t remote_frames = 0;        // remote requests with a mapped id
  std::uint64_t error_frames = 0;         // kernel error frames passed in (decoded by the receiver)
  std::uint64_t full_scale_values = 0;    // axis values at their signal's full scale (saturated; used as read)
};

// Calls fn(name, value) for the counters a STATUS report shows, in a fixed order, with stable
// snake_case names (not frames and decoded_frames: each source counts the frames it reads).
template <class Fn>
void forEachCounter(const AssemblerCounters& a, Fn&& fn) {
  fn("samples", a.samples);
  fn("samples_with_mag", a.samples_with_mag);
  fn("incomplete_epochs", a.incomplete_epochs);
  fn("sequence_gaps", a.sequence_gaps);
  fn("missing_epochs", a.missing_epochs);
  fn("reordered_epochs", a.reordered_epochs);
  fn("duplicate_frames", a.duplicate_frames);
  fn("late_frames", a.late_frames);
  fn("late_mag_frames", a.late_mag_frames);
  fn("unknown_id_frames", a.unknown_id_frames);
  fn("wrong_length_frames", a.wrong_length_frames);
  fn("error_frames", a.error_frames);
  fn("superseded_mag_frames", a.superseded_mag);
  fn("remote_frames", a.remote_frames);
  fn("full_scale_values", a.full_scale_values);
}

struct AssembledSamples {
  int count = 0;  // 0, 1 or 2 (a frame can close one epoch and complete the next)
  std::array<core::ImuSample, 2> samples;
};

class EpochAssembler {
 public:
  EpochAssembler(const ImuFrameCodec& codec, EpochSettings settings);

  AssembledSamples push(const CanFrame& frame);
  // Releases (or counts as incomplete) an open epoch whose first frame is older than the
  // window at `now_ns` (same clock as the frames' t_ns).
  AssembledSamples flush(std::int64_t now_ns);
  // End of input: closes the open epoch.
  AssembledSamples finish();
  // The frames that follow are a stream of their own (a log played again from its start):
  // closes the open epoch and forgets the last one released and a carried magnetometer
  // reading, so that the new stream's first counters are not taken for late or repeated
  // frames of the old one.
  AssembledSamples restartStream();

  const AssemblerCounters& counters() const { return counters_; }
  // True while an epoch is being collected (flush() or finish() would close it).
  bool hasOpenEpoch() const { return pending_.valid; }

 private:
  struct EpochKey {
    bool valid = false;
    bool has_sequence = false;
    std::uint64_t sequence = 0;
    std::int64_t t_first_ns = 0;
    std::uint16_t axis_mask = 0;
  };
  bool sameEpoch(const EpochKey& key, const DecodedFrame& d, std::int64_t t_ns) const;
  void open(const DecodedFrame& d, std::int64_t t_ns);
  // Counts a new epoch's counter: a skip ahead (sequence_gaps, missing_epochs) or an epoch up
  // to reorder_window_ behind the newest (reordered_epochs; no longer missing if it was).
  void countSequence(std::uint64_t sequence);
  void add(const DecodedFrame& d);
  void close(AssembledSamples& out);
  void release(AssembledSamples& out);

  const ImuFrameCodec& codec_;
  EpochSettings settings_;
  std::uint16_t required_mask_ = 0;
  std::uint64_t sequence_mask_ = 0;
  EpochKey pending_;  // the epoch being collected (valid = open)
  std::array<double, kAxisCount> values_{};
  EpochKey released_;  // the last epoch released, to recognise late frames
  bool have_last_sequence_ = false;
  std::uint64_t last_sequence_ = 0;  // the newest epoch's counter
  std::uint64_t reorder_window_ = 1;
  std::uint64_t missing_recent_ = 0;  // bit k: the epoch k + 1 behind the newest was skipped
  bool carried_mag_valid_ = false;
  std::array<double, 3> carried_mag_{};
  AssemblerCounters counters_;
};

}  // namespace headingd::can
