#pragma once
// The accelerometer's gyro-frame low-pass (gyro_frame_low_pass.hpp) that averages longer
// while the body keeps turning about the vertical.
//
// A person who runs or walks round a bend feels the centripetal acceleration v·Ω (speed times
// turn rate) towards the inside of the bend: a fixed direction in the body, about 2.7 m/s²
// (16°) running at 3 m/s round a room at 0.9 rad/s. Gravity is fixed in the gyro frame; that
// acceleration turns in it at Ω, so a low-pass of time constant τ there keeps
// v·Ω / √(1 + (Ωτ)²) of it, never more than v/τ: at τ = 2 s the apparent gravity leans
// about 4° into the bend for as long as the turning lasts (the shared phone recordings'
// runs round the room: the low-pass's output 5.1° RMS from the optical vertical, and a steady
// inclination error of 3.4°). A longer time constant shrinks it in proportion, and costs
// little while the turning is about the vertical: the gyro frame's errors about the vertical
// do not move gravity in it.
//
// Two low-passes run side by side, τ₀ and τ₁ > τ₀, and the output moves from the first to the
// second as the rate about the vertical while the body steps (walks or runs: the motion level
// of Henriksson §3.1 above standing), low-passed over τ₀ (turns back and forth, a hand, a
// shake, count little; a bend does), grows to Ω_full: y = (1 - w) y₀ + w y₁,
// w = min(1, |Ω̄| / Ω_full) · clamp(2 - |ω̄| / ω_max, 0, 1).
//
// Only while stepping: without a speed there is no bend's acceleration, and a sensor turned
// in place (BROAD's slow rotations, standing level 98 % of the time) lost inclination to the
// long average (trial 01: 0.51° without it, 0.88° with it).
//
// Why two filters blended and not one whose τ follows the turning: a single filter whose
// time constant changes weights each sample by when it came, and when the changes follow the
// motion those weights follow its accelerations, which then no longer average out (the low-pass's output on BROAD's
// trial 30, fast rotations, computed offline with the optical vertical: 3.0° RMS from the vertical at a fixed 2 s, 4.3°
// with τ following the turning, 1.7° blended).
//
// The blend's weight also falls as the body's whole rate grows beyond ω_max, to nothing at
// 2 ω_max: the gyro frame's errors (scale, misalignment) grow with the rotation, and BROAD's
// hand-held fast rotations (6-7 rad/s, a quarter of it about the vertical) lost inclination
// to the long average (trial 21: 1.38° without it, 2.04° with it unfaded, 1.44° faded); no
// one runs round a bend at 7 rad/s.
#include <algorithm>
#include <cmath>

#include "headingd/core/gyro_frame_low_pass.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// How far a sample is into a steady turn about the vertical: w above.
class SteadyTurnWeight {
 public:
  // average_time_constant_s: of the rates' low-passes (τ₀); full_turn_rate_rad_s: Ω_full (0:
  // w is always 0); max_rate_rad_s: ω_max.
  SteadyTurnWeight(double average_time_constant_s, double full_turn_rate_rad_s, double max_rate_rad_s)
      : full_rate_(full_turn_rate_rad_s),
        max_rate_(max_rate_rad_s),
        vertical_rate_(average_time_constant_s),
        rate_(average_time_constant_s),
        time_constant_s_(average_time_constant_s) {}

  // gyro_rad_s: this sample's rate in sensor axes, bias taken off; down_s: NED down in sensor
  // axes (the attitude's); stepping: the body walks or runs (motion level above standing),
  // else its turns count as none. Returns w in [0, 1].
  double update(const Vec3& gyro_rad_s, const Vec3& down_s, bool stepping, double dt_s) {
    if (full_rate_ <= 0.0) return 0.0;
    const double vertical_rate = stepping ? gyro_rad_s.dot(down_s) : 0.0;
    const double turning = std::min(1.0, std::abs(vertical_rate_.update(vertical_rate, dt_s)) / full_rate_);
    const double slow_enough = std::clamp(2.0 - rate_.update(gyro_rad_s.norm(), dt_s) / max_rate_, 0.0, 1.0);
    return turning * slow_enough;
  }
  // Forget the turning (after a gap).
  void restart() {
    vertical_rate_ = LowPass<double>(time_constant_s_);
    rate_ = LowPass<double>(time_constant_s_);
  }

 private:
  double full_rate_;
  double max_rate_;
  LowPass<double> vertical_rate_;  // rad/s about NED down
  LowPass<double> rate_;           // |ω|, rad/s
  double time_constant_s_;
};

// y₀ and y₁ and their blend. Off (the raw sample through) when τ₀ is 0; y₀ alone when τ₁ is 0.
// Both start as the running mean of their samples (gyro_frame_low_pass.hpp): a recording that
// starts in motion (a phone taken out running) otherwise carries its first sample's
// accelerations for seconds (the shared iPhone 4S running in the hand: the tilt 18° off two
// seconds in, where VQF, whose low-pass starts the same way, is 4° off).
class TurnBlendedLowPass {
 public:
  TurnBlendedLowPass(double time_constant_s, double turning_time_constant_s)
      : short_(time_constant_s, GyroFrameStart::kRunningMean),
        long_(time_constant_s > 0.0 ? turning_time_constant_s : 0.0, GyroFrameStart::kRunningMean),
        blended_(time_constant_s > 0.0 && turning_time_constant_s > 0.0) {}

  // As GyroFrameLowPass: the frame follows every gyro increment; add() takes a sample and
  // returns the blend for weight w (SteadyTurnWeight) in the current body axes.
  void advance(const Quat& increment) {
    short_.advance(increment);
    if (blended_) long_.advance(increment);
  }
  Vec3 add(const Vec3& body_vector, double dt_s, double w) {
    y0_ = short_.add(body_vector, dt_s);
    if (!blended_) return y0_;
    const Vec3 y1 = long_.add(body_vector, dt_s);
    return y0_ + w * (y1 - y0_);
  }
  // y₀ of the last sample added.
  const Vec3& shortAverage() const { return y0_; }
  Vec3 update(const Quat& increment, const Vec3& body_vector, double dt_s, double w) {
    advance(increment);
    return add(body_vector, dt_s, w);
  }
  void restart() {
    short_.restart();
    long_.restart();
  }

 private:
  GyroFrameLowPass short_;
  GyroFrameLowPass long_;
  bool blended_;
  Vec3 y0_ = Vec3::Zero();
};

}  // namespace headingd::core
