#include "headingd/sim/motion_scenarios.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/sim/rng.hpp"

namespace headingd::sim {

namespace {

using core::Quat;
using core::Vec3;

constexpr double kG = 9.80665;
using core::kDegPerRad;

// Stream ids for the motion draws (independent of simulation.cpp's sensor streams).
enum MotionStream : std::uint64_t { kShake = 101, kHandheld, kSlowRotation, kAttitude };

OrientationKeyframe keyframe(double t_s, const Quat& q) {
  const core::EulerAngles e = core::eulerZyx(q);
  return {t_s, e.roll_rad * kDegPerRad, e.pitch_rad * kDegPerRad, e.yaw_rad * kDegPerRad};
}

// The time of the next keyframe, step_s after t_s, but never past end_s and never leaving a
// last move shorter than min_step_s before it (the scenario's length is fixed).
double nextKeyframeTime(double t_s, double step_s, double end_s, double min_step_s) {
  const double next = t_s + step_s;
  return end_s - next < min_step_s ? end_s : next;
}

void hold(ScriptedOrientation& s, double duration_s) {
  OrientationKeyframe k = s.keyframes.back();
  k.t_s += duration_s;
  s.keyframes.push_back(k);
}

}  // namespace

Quat uniformAttitude(std::uint64_t seed, std::uint64_t stream_id) {
  Rng rng = Rng::stream(seed, stream_id);
  for (;;) {
    const Quat q(rng.gaussian(), rng.gaussian(), rng.gaussian(), rng.gaussian());
    if (q.norm() > 1e-6) return q.normalized();
  }
}

Scenario shakeScenario(const ShakeSpec& spec, std::string name, std::string description) {
  ScriptedOrientation script;
  script.tremor_deg = spec.tremor_deg;
  script.hand_drift_deg = spec.hand_drift_deg;
  const double end = spec.still_before_s + spec.shake_s + spec.still_after_s;
  script.keyframes = {keyframe(0.0, spec.initial_attitude), keyframe(end, spec.initial_attitude)};
  LinearShake shake;
  shake.direction_body = spec.direction_body.normalized();
  shake.peak_accel_m_s2 = spec.peak_accel_m_s2;
  shake.frequency_hz = spec.frequency_hz;
  shake.start_s = spec.still_before_s;
  shake.end_s = spec.still_before_s + spec.shake_s;
  shake.fade_s = 1.0;
  script.shakes = {shake};
  return scriptedScenario(std::move(name), std::move(description), std::move(script));
}

ShakeSpec drawShakeAlongSensorAxis(std::uint64_t seed) {
  Rng rng = Rng::stream(seed, kShake);
  ShakeSpec spec;
  spec.initial_attitude = uniformAttitude(seed, kAttitude);
  const int axis = std::min(2, static_cast<int>(rng.uniform(0.0, 3.0)));
  spec.direction_body = Vec3::Unit(axis) * (rng.uniform01() < 0.5 ? -1.0 : 1.0);
  spec.frequency_hz = rng.uniform(2.0, 8.0);
  spec.peak_accel_m_s2 = rng.uniform(2.0, 7.0) * kG;
  return spec;
}

ShakeSpec drawShakeAnyDirection(std::uint64_t seed) {
  Rng rng = Rng::stream(seed, kShake);
  ShakeSpec spec;
  spec.initial_attitude = uniformAttitude(seed, kAttitude);
  spec.direction_body = rng.unitVector();
  spec.frequency_hz = rng.uniform(0.5, 10.0);
  spec.peak_accel_m_s2 = rng.uniform(0.5, 8.0) * kG;
  return spec;
}

Scenario handheldScenario(std::uint64_t seed) {
  Rng rng = Rng::stream(seed, kHandheld);
  ScriptedOrientation script;
  script.tremor_deg = 0.03;
  script.hand_drift_deg = 2.0;
  script.lever_arm_body_m = 0.15 * rng.unitVector();
  script.keyframes = {keyframe(0.0, uniformAttitude(seed, kAttitude))};
  hold(script, 10.0);
  const double handling_end = 70.0;
  while (script.keyframes.back().t_s < handling_end) {
    OrientationKeyframe k = script.keyframes.back();
    k.t_s = nextKeyframeTime(k.t_s, rng.uniform(0.4, 1.2), handling_end, 0.4);
    k.roll_deg += rng.uniform(-120.0, 120.0);
    k.pitch_deg = std::clamp(k.pitch_deg + rng.uniform(-90.0, 90.0), -85.0, 85.0);
    k.yaw_deg += rng.uniform(-150.0, 150.0);
    script.keyframes.push_back(k);
    if (rng.uniform01() < 0.3 && k.t_s < handling_end - 1.0) hold(script, rng.uniform(0.1, 0.6));
  }
  // The hand's own translations while it turns the sensor.
  for (int i = 0; i < 3; ++i) {
    LinearShake shake;
    shake.direction_body = rng.unitVector();
    shake.frequency_hz = rng.uniform(0.5, 3.0);
    shake.peak_accel_m_s2 = rng.uniform(0.5, 2.0) * kG;
    shake.start_s = 10.0;
    shake.end_s = script.keyframes.back().t_s;
    script.shakes.push_back(shake);
  }
  hold(script, 30.0);
  return scriptedScenario("handheld",
                          "Vigorous hand-held handling (seeded): 10 s still, ~60 s of turning to a new attitude every "
                          "0.4-1.2 s (rates up to ~600 deg/s) while the hand moves at 0.5-3 Hz and 0.5-2 g, sensor "
                          "15 cm from the wrist; 30 s still.",
                          std::move(script));
}

Scenario slowRotationScenario(std::uint64_t seed) {
  Rng rng = Rng::stream(seed, kSlowRotation);
  ScriptedOrientation script;
  script.tremor_deg = 0.1;
  script.hand_drift_deg = 0.5;
  script.keyframes = {{0.0, rng.uniform(-20.0, 20.0), rng.uniform(-20.0, 20.0), rng.uniform(-180.0, 180.0)}};
  hold(script, 10.0);
  const double turning_end = 100.0;
  while (script.keyframes.back().t_s < turning_end) {
    OrientationKeyframe k = script.keyframes.back();
    k.t_s = nextKeyframeTime(k.t_s, rng.uniform(3.0, 8.0), turning_end, 3.0);
    k.roll_deg = rng.uniform(-60.0, 60.0);
    k.pitch_deg = rng.uniform(-60.0, 60.0);
    k.yaw_deg += rng.uniform(-120.0, 120.0);
    script.keyframes.push_back(k);
    if (rng.uniform01() < 0.2 && k.t_s < turning_end - 3.0) hold(script, rng.uniform(0.5, 2.0));
  }
  hold(script, 20.0);
  return scriptedScenario("slow-rotation",
                          "Gentle slow rotation (seeded): 10 s still, ~90 s of turning to a new attitude every 3-8 s "
                          "(tilt up to 60 deg, rates mostly 2-25 deg/s), 20 s still.",
                          std::move(script));
}

}  // namespace headingd::sim
