#include "headingd/sim/walking_trajectory.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/sim/carry.hpp"
#include "headingd/sim/gait.hpp"

namespace headingd::sim {

namespace {

using core::Quat;
using core::Vec3;

constexpr double kPi = std::numbers::pi;
using core::kRadPerDeg;

// A smooth zero-mean signal: a few slow sinusoids with seeded amplitudes, frequencies and
// phases. Smooth, so it can modulate speed and heading without jerky accelerations.
class SlowWander {
 public:
  SlowWander(Rng& rng, double amplitude_lo, double amplitude_hi, double freq_lo_hz, double freq_hi_hz) {
    for (auto& c : terms_) {
      c = {rng.uniform(amplitude_lo, amplitude_hi), 2.0 * kPi * rng.uniform(freq_lo_hz, freq_hi_hz),
           rng.uniform(0.0, 2.0 * kPi)};
    }
  }
  double operator()(double t) const {
    double sum = 0.0;
    for (const auto& c : terms_) sum += c[0] * std::sin(c[1] * t + c[2]);
    return sum;
  }

 private:
  std::array<std::array<double, 3>, 3> terms_{};
};

// Heading from all turns that have started by t (each a smootherstep in time).
double turnedHeadingRad(const Scenario& s, double t) {
  double heading = s.initial_heading_deg * kRadPerDeg;
  double start = 0.0;
  for (const Phase& p : s.phases) {
    for (const Turn& turn : p.turns) {
      const double s01 = turn.duration_s > 0.0 ? (t - start - turn.start_s) / turn.duration_s
                                               : (t >= start + turn.start_s ? 1.0 : 0.0);
      heading += turn.angle_deg * kRadPerDeg * smootherstep(s01);
    }
    start += p.duration_s;
  }
  return heading;
}

// Gait and posture at t, blended from the previous phase's during this phase's transition.
struct PhaseState {
  GaitParams gait;
  bool changing_posture = false;
};

// A phase held still has no postural sway (its attitude is constant).
GaitParams phaseGait(const Phase& p) {
  GaitParams g = gaitParams(p.activity);
  if (p.held_still) g.sway_deg = 0.0;
  g.speed_mps *= p.speed_scale;
  return g;
}

PhaseState phaseState(const Scenario& s, double t) {
  const PhaseTime pt = phaseAt(s, t);
  const Activity current = s.phases[pt.index].activity;
  GaitParams target = phaseGait(s.phases[pt.index]);
  if (pt.index == 0 || pt.since_start_s >= target.transition_s) return {target, false};
  const Activity previous = s.phases[pt.index - 1].activity;
  return {blend(phaseGait(s.phases[pt.index - 1]), target, smootherstep(pt.since_start_s / target.transition_s)),
          previous != current};
}

}  // namespace

Trajectory generateWalkingTrajectory(const Scenario& scenario, double rate_hz, Rng rng) {
  requirePositiveRateAndPhases(scenario, rate_hz);
  const double dt = 1.0 / rate_hz;
  const auto rows = static_cast<std::size_t>(std::floor(scenario.durationS() * rate_hz + 1e-9)) + 1;

  const SlowWander speed_modulation(rng, 0.005, 0.015, 0.01, 0.08);  // a few % of speed
  const SlowWander heading_wander(rng, 0.5 * kRadPerDeg, 1.0 * kRadPerDeg, 0.005, 0.05);

  // One extra sample before t = 0 and after the end, for the central differences.
  const std::size_t n = rows + 2;
  std::vector<Vec3> position(n);
  std::vector<Quat> attitude(n);
  std::vector<Quat> q_b_sensor(n, Quat::Identity());
  std::vector<double> path_heading(n);
  std::vector<PhaseState> phase_state(n);
  Vec3 path = Vec3::Zero();  // integrated horizontal path, NED
  Vec3 previous_velocity = Vec3::Zero();
  double step_phase = 0.0;  // radians, one cycle per step
  double previous_step_hz = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = (static_cast<double>(i) - 1.0) * dt;
    const PhaseState ps = phaseState(scenario, t);
    const GaitParams& g = ps.gait;
    const double modulation = speed_modulation(t);
    // Wandering off a straight line only happens while going somewhere.
    const double locomotion = std::min(1.0, g.speed_mps / 1.0);
    const double heading = turnedHeadingRad(scenario, t) + locomotion * heading_wander(t);
    const double speed = g.speed_mps * (1.0 + modulation);
    const double step_hz = g.step_hz * (1.0 + 0.5 * modulation);
    const Vec3 velocity(speed * std::cos(heading), speed * std::sin(heading), 0.0);
    if (i > 0) {
      path += 0.5 * dt * (previous_velocity + velocity);  // trapezoid
      step_phase += kPi * dt * (previous_step_hz + step_hz);
    }
    previous_velocity = velocity;
    previous_step_hz = step_hz;

    // Gait excursions in the heading frame (forward, right, down), then in NED.
    const Vec3 excursion_h(g.forward_m * std::sin(step_phase), g.lateral_m * std::sin(0.5 * step_phase),
                           g.vertical_m * std::cos(step_phase));
    const Vec3 excursion = core::headingRotation(heading) * excursion_h;
    position[i] = path + excursion + Vec3(0.0, 0.0, -g.height_m);

    const double sway = 2.0 * kPi * kSwayHz * t;
    const double yaw = heading + g.osc_yaw_deg * kRadPerDeg * std::cos(0.5 * step_phase);
    const double pitch =
        (g.pitch_deg + g.osc_pitch_deg * std::sin(step_phase + 0.25 * kPi) + g.sway_deg * std::sin(sway)) * kRadPerDeg;
    const double roll =
        (g.roll_deg + g.osc_roll_deg * std::sin(0.5 * step_phase) + g.sway_deg * std::sin(1.3 * sway + 1.0)) *
        kRadPerDeg;
    attitude[i] = (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                   Eigen::AngleAxisd(roll, Vec3::UnitX()))
                      .normalized();
    if (scenario.carry) {
      // A carried phone: the sensor's place and attitude follow the limb it rides on.
      const CarryPose pose = carryPose(*scenario.carry, g, 0.5 * step_phase);
      position[i] += attitude[i] * pose.offset_body_m;
      q_b_sensor[i] = pose.q_b_sensor;
    }
    path_heading[i] = heading;
    phase_state[i] = ps;
  }

  // The person starts at the origin (the ground under the IMU at t = 0).
  const Vec3 origin(position[1].x(), position[1].y(), 0.0);
  for (Vec3& p : position) p -= origin;

  Trajectory out = kinematicTrajectory(scenario, rate_hz, attitude, position);
  out.q_b_sensor_before_start = q_b_sensor[0];
  for (std::size_t k = 0; k < out.states.size(); ++k) {
    const std::size_t i = k + 1;
    TruthState& s = out.states[k];
    s.q_b_sensor = q_b_sensor[i];
    s.path_heading_rad = path_heading[i];
    const double turn_rate = std::abs(core::wrapAngle(path_heading[i + 1] - path_heading[i - 1])) / (2.0 * dt);
    s.moving = phase_state[i].gait.speed_mps > 0.05 || turn_rate > 1.0 * kRadPerDeg || phase_state[i].changing_posture;
  }
  return out;
}

}  // namespace headingd::sim
