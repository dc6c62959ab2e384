#include "headingd/can/epoch_assembler.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace headingd::can {

EpochSettings epochSettingsFrom(const CanConfig& config) {
  EpochSettings s;
  s.window_ns = std::llround(config.epoch_window_s * 1e9);
  s.wait_for_mag = config.epoch_waits_for_mag;
  return s;
}

EpochAssembler::EpochAssembler(const ImuFrameCodec& codec, EpochSettings settings)
    : codec_(codec), settings_(settings) {
  required_mask_ = kGyroAxes | kAccelAxes;
  if (settings_.wait_for_mag && codec_.hasMag()) required_mask_ |= kMagAxes;
  const unsigned bits = codec_.sequenceBits();
  sequence_mask_ = bits == 0 ? 0 : (bits >= 64 ? ~0ull : (1ull << bits) - 1);
  // A quarter of the counter's range (at most 64) behind the newest is "late", the rest
  // "ahead": a 4-bit counter tells 4 epochs late from a skip of up to 11.
  reorder_window_ =
      std::max<std::uint64_t>(1, std::min<std::uint64_t>(64, (sequence_mask_ >> 2) + (bits >= 2 ? 1 : 0)));
}

bool EpochAssembler::sameEpoch(const EpochKey& key, const DecodedFrame& d, std::int64_t t_ns) const {
  if (!key.valid) return false;
  if (key.has_sequence && d.has_sequence) return key.sequence == d.sequence;
  const std::int64_t dt = t_ns - key.t_first_ns;
  return dt <= settings_.window_ns && dt >= -settings_.window_ns;
}

void EpochAssembler::open(const DecodedFrame& d, std::int64_t t_ns) {
  pending_ = EpochKey{true, d.has_sequence, d.sequence, t_ns, 0};
  if (d.has_sequence) countSequence(d.sequence);
}

void EpochAssembler::countSequence(std::uint64_t sequence) {
  if (!have_last_sequence_) {
    have_last_sequence_ = true;
    last_sequence_ = sequence;
    return;
  }
  const std::uint64_t ahead = (sequence - last_sequence_) & sequence_mask_;
  const std::uint64_t behind = (last_sequence_ - sequence) & sequence_mask_;
  if (ahead == 0) return;  // the newest epoch's counter again (a late frame of it): nothing skipped
  if (ahead != 1 && behind <= reorder_window_) {
    // An epoch that arrives after a newer one: reordered, not a skip of nearly the whole
    // counter range. If it was counted missing, it no longer is.
    ++counters_.reordered_epochs;
    const std::uint64_t bit = 1ull << (behind - 1);
    if ((missing_recent_ & bit) != 0) {
      missing_recent_ &= ~bit;
      --counters_.missing_epochs;
      const bool newer_missing = behind >= 2 && (missing_recent_ & (bit >> 1)) != 0;
      const bool older_missing = behind < 64 && (missing_recent_ & (bit << 1)) != 0;
      if (!newer_missing && !older_missing && counters_.sequence_gaps > 0) --counters_.sequence_gaps;  // gap filled
      if (newer_missing && older_missing) ++counters_.sequence_gaps;  // its gap is split in two
    }
    return;  // the counter stays at the newest epoch
  }
  if (ahead > 1) {
    ++counters_.sequence_gaps;
    counters_.missing_epochs += ahead - 1;
  }
  // Bit k: the epoch k + 1 behind the newest was skipped.
  missing_recent_ = ahead >= 64 ? 0 : missing_recent_ << ahead;
  const std::uint64_t skipped = std::min<std::uint64_t>(ahead - 1, 64);
  if (skipped > 0) missing_recent_ |= skipped == 64 ? ~0ull : (1ull << skipped) - 1;
  last_sequence_ = sequence;
}

void EpochAssembler::add(const DecodedFrame& d) {
  for (int axis = 0; axis < kAxisCount; ++axis) {
    if ((d.axis_mask & (1u << axis)) != 0)
      values_[static_cast<std::size_t>(axis)] = d.values[static_cast<std::size_t>(axis)];
  }
  pending_.axis_mask = static_cast<std::uint16_t>(pending_.axis_mask | d.axis_mask);
}

void EpochAssembler::release(AssembledSamples& out) {
  core::ImuSample& s = out.samples[static_cast<std::size_t>(out.count++)];
  s.t_ns = pending_.t_first_ns;
  s.gyro_rad_s = {values_[0], values_[1], values_[2]};
  s.accel_m_s2 = {values_[3], values_[4], values_[5]};
  if ((pending_.axis_mask & kMagAxes) == kMagAxes) {
    s.mag_uT = {values_[6], values_[7], values_[8]};
    s.has_mag = true;
    if (carried_mag_valid_) ++counters_.superseded_mag;
    carried_mag_valid_ = false;
  } else if (carried_mag_valid_) {
    s.mag_uT = {carried_mag_[0], carried_mag_[1], carried_mag_[2]};
    s.has_mag = true;
    carried_mag_valid_ = false;
  } else {
    s.mag_uT = core::Vec3::Zero();
    s.has_mag = false;
  }
  ++counters_.samples;
  if (s.has_mag) ++counters_.samples_with_mag;
  released_ = pending_;
  pending_.valid = false;
}

void EpochAssembler::close(AssembledSamples& out) {
  if (!pending_.valid) return;
  if ((pending_.axis_mask & (kGyroAxes | kAccelAxes)) == (kGyroAxes | kAccelAxes)) {
    release(out);
    return;
  }
  ++counters_.incomplete_epochs;
  if ((pending_.axis_mask & kMagAxes) == kMagAxes) {
    // A real magnetometer reading whose gyro/accel frames were lost: still fresh for the next sample.
    if (carried_mag_valid_) ++counters_.superseded_mag;
    carried_mag_ = {values_[6], values_[7], values_[8]};
    carried_mag_valid_ = true;
  }
  pending_.valid = false;
}

AssembledSamples EpochAssembler::push(const CanFrame& frame) {
  AssembledSamples out;
  ++counters_.frames;
  DecodedFrame d;
  switch (codec_.decode(frame, d)) {
    case DecodeStatus::decoded: break;
    case DecodeStatus::unknown_id: ++counters_.unknown_id_frames; return out;
    case DecodeStatus::wrong_length: ++counters_.wrong_length_frames; return out;
    case DecodeStatus::remote_frame: ++counters_.remote_frames; return out;
    case DecodeStatus::error_frame: ++counters_.error_frames; return out;
  }
  ++counters_.decoded_frames;
  counters_.full_scale_values += static_cast<std::uint64_t>(std::popcount(d.full_scale_mask));
  const std::int64_t t = frame.t_ns;
  const bool counted = d.has_sequence && pending_.has_sequence;

  if (sameEpoch(pending_, d, t)) {
    if ((pending_.axis_mask & d.axis_mask) == 0) {
      add(d);
    } else if (counted) {
      ++counters_.duplicate_frames;  // same counter, same message again: keep the first
      return out;
    } else {
      close(out);  // an axis repeats: without counters that is the next epoch
      open(d, t);
      add(d);
    }
  } else if (released_.valid && !pending_.valid && sameEpoch(released_, d, t) &&
             (released_.axis_mask & d.axis_mask) == 0) {
    if ((d.axis_mask & ~kMagAxes) == 0) {
      ++counters_.late_mag_frames;
      if (carried_mag_valid_) ++counters_.superseded_mag;
      carried_mag_ = {d.values[6], d.values[7], d.values[8]};
      carried_mag_valid_ = true;
    } else {
      ++counters_.late_frames;
    }
    released_.axis_mask = static_cast<std::uint16_t>(released_.axis_mask | d.axis_mask);
    return out;
  } else if (released_.valid && d.has_sequence && released_.has_sequence && d.sequence == released_.sequence) {
    // The released epoch's counter again: a late or repeated frame, not a new epoch.
    if ((released_.axis_mask & d.axis_mask) == 0 && (d.axis_mask & ~kMagAxes) == 0) {
      ++counters_.late_mag_frames;
      if (carried_mag_valid_) ++counters_.superseded_mag;
      carried_mag_ = {d.values[6], d.values[7], d.values[8]};
      carried_mag_valid_ = true;
      released_.axis_mask = static_cast<std::uint16_t>(released_.axis_mask | d.axis_mask);
    } else if ((released_.axis_mask & d.axis_mask) == 0) {
      ++counters_.late_frames;
    } else {
      ++counters_.duplicate_frames;
    }
    return out;
  } else {
    close(out);
    open(d, t);
    add(d);
  }
  if ((pending_.axis_mask & required_mask_) == required_mask_) release(out);
  return out;
}

AssembledSamples EpochAssembler::flush(std::int64_t now_ns) {
  AssembledSamples out;
  if (pending_.valid && now_ns - pending_.t_first_ns > settings_.window_ns) close(out);
  return out;
}

AssembledSamples EpochAssembler::finish() {
  AssembledSamples out;
  close(out);
  return out;
}

AssembledSamples EpochAssembler::restartStream() {
  AssembledSamples out = finish();
  released_ = EpochKey{};
  carried_mag_valid_ = false;
  return out;
}

}  // namespace headingd::can
