#include "headingd/sim/scripted_trajectory.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "headingd/core/angles.hpp"
#include "headingd/sim/gait.hpp"
#include "headingd/sim/imu_model.hpp"
#include "headingd/sim/trajectory.hpp"

namespace headingd::sim {

namespace {

using core::Quat;
using core::Vec3;

constexpr double kPi = std::numbers::pi;
using core::kRadPerDeg;

Quat fromEulerZyx(double roll_rad, double pitch_rad, double yaw_rad) {
  return (Eigen::AngleAxisd(yaw_rad, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch_rad, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll_rad, Vec3::UnitX()))
      .normalized();
}

// A small rotation vector that wanders: per axis, a few sinusoids with seeded amplitudes,
// frequencies and phases (the amplitudes sum to at most `amplitude_rad`).
class RotationWobble {
 public:
  RotationWobble(Rng& rng, double amplitude_rad, double freq_lo_hz, double freq_hi_hz) {
    for (auto& axis : terms_) {
      for (auto& c : axis) {
        c = {amplitude_rad * rng.uniform(0.1, 1.0 / 3.0), 2.0 * kPi * rng.uniform(freq_lo_hz, freq_hi_hz),
             rng.uniform(0.0, 2.0 * kPi)};
      }
    }
  }
  Vec3 operator()(double t) const {
    Vec3 v = Vec3::Zero();
    for (int a = 0; a < 3; ++a) {
      for (const auto& c : terms_[static_cast<std::size_t>(a)]) v(a) += c[0] * std::sin(c[1] * t + c[2]);
    }
    return v;
  }

 private:
  std::array<std::array<std::array<double, 3>, 3>, 3> terms_{};
};

Quat rotationVector(const Vec3& v) {
  const double angle = v.norm();
  if (angle < 1e-15) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, v / angle));
}

// Displacement along the shake direction (sensor axes) at t, and whether it is under way.
double shakeEnvelope(const LinearShake& shake, double t) {
  if (t <= shake.start_s || t >= shake.end_s) return 0.0;
  const double fade = std::max(shake.fade_s, 1e-9);
  return smootherstep((t - shake.start_s) / fade) * smootherstep((shake.end_s - t) / fade);
}

double shakeDisplacement(const LinearShake& shake, double t) {
  const double omega = 2.0 * kPi * shake.frequency_hz;
  return -(shake.peak_accel_m_s2 / (omega * omega)) * shakeEnvelope(shake, t) * std::sin(omega * (t - shake.start_s));
}

}  // namespace

Quat scriptedAttitude(const ScriptedOrientation& script, double t_s) {
  const auto& k = script.keyframes;
  if (k.empty()) return Quat::Identity();
  std::size_t i = 0;
  while (i + 1 < k.size() && t_s >= k[i + 1].t_s) ++i;
  if (i + 1 == k.size() || t_s <= k[i].t_s) {
    const OrientationKeyframe& f = t_s <= k.front().t_s ? k.front() : k[i];
    return fromEulerZyx(f.roll_deg * kRadPerDeg, f.pitch_deg * kRadPerDeg, f.yaw_deg * kRadPerDeg);
  }
  const OrientationKeyframe& a = k[i];
  const OrientationKeyframe& b = k[i + 1];
  const double w = smootherstep((t_s - a.t_s) / (b.t_s - a.t_s));
  const auto lerp = [w](double x, double y) { return (x + w * (y - x)) * kRadPerDeg; };
  return fromEulerZyx(lerp(a.roll_deg, b.roll_deg), lerp(a.pitch_deg, b.pitch_deg), lerp(a.yaw_deg, b.yaw_deg));
}

Trajectory generateScriptedTrajectory(const Scenario& scenario, double rate_hz, Rng rng) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw std::invalid_argument("IMU rate must be positive");
  if (!scenario.scripted || scenario.scripted->keyframes.empty() || scenario.phases.empty()) {
    throw std::invalid_argument("scenario has no scripted orientation");
  }
  const ScriptedOrientation& script = *scenario.scripted;
  for (std::size_t i = 1; i < script.keyframes.size(); ++i) {
    if (!(script.keyframes[i].t_s > script.keyframes[i - 1].t_s)) {
      throw std::invalid_argument("scripted keyframes must be in increasing time order");
    }
  }
  for (const LinearShake& shake : script.shakes) {
    if (!(shake.frequency_hz > 0.0) || !(shake.end_s >= shake.start_s) ||
        std::abs(shake.direction_body.norm() - 1.0) > 1e-9) {
      throw std::invalid_argument("a shake needs a positive frequency, end >= start and a unit direction");
    }
  }
  const double dt = 1.0 / rate_hz;
  const auto rows = static_cast<std::size_t>(std::floor(scenario.durationS() * rate_hz + 1e-9)) + 1;
  // Physiological tremor 6-12 Hz; the hand's slow drift 0.1-0.5 Hz.
  const RotationWobble tremor(rng, script.tremor_deg * kRadPerDeg, 6.0, 12.0);
  const RotationWobble drift(rng, script.hand_drift_deg * kRadPerDeg, 0.1, 0.5);
  const Vec3 centre(0.0, 0.0, -script.height_m);

  // One extra sample before t = 0 and after the end, for the central differences.
  const std::size_t n = rows + 2;
  std::vector<Quat> attitude(n), scripted(n);
  std::vector<Vec3> position(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = (static_cast<double>(i) - 1.0) * dt;
    scripted[i] = scriptedAttitude(script, t);
    attitude[i] = (scripted[i] * rotationVector(tremor(t) + drift(t))).normalized();
    Vec3 offset_body = script.lever_arm_body_m;
    for (const LinearShake& shake : script.shakes) offset_body += shakeDisplacement(shake, t) * shake.direction_body;
    position[i] = centre + attitude[i] * offset_body;
  }

  Trajectory out = kinematicTrajectory(scenario, rate_hz, attitude, position);
  for (std::size_t k = 0; k < out.states.size(); ++k) {
    const std::size_t i = k + 1;
    TruthState& s = out.states[k];
    s.path_heading_rad = core::eulerZyx(scripted[i]).yaw_rad;
    const double scripted_rate = rateBetween(scripted[i - 1], scripted[i + 1], 2.0 * dt).norm();
    bool shaking = false;
    for (const LinearShake& shake : script.shakes) shaking = shaking || shakeEnvelope(shake, s.t_s) > 0.0;
    s.moving = scripted_rate > script.moving_rate_deg_s * kRadPerDeg || shaking;
  }
  return out;
}

}  // namespace headingd::sim
