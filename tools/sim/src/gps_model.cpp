#include "headingd/sim/gps_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"

namespace headingd::sim {

namespace {

using core::Vec3;
constexpr double kPi = std::numbers::pi;

double courseDeg(double north, double east) {
  const double c = std::atan2(east, north) * core::kDegPerRad;
  return c < 0.0 ? c + 360.0 : (c >= 360.0 ? c - 360.0 : c);
}

// The true position at t, linearly interpolated between the IMU samples around it.
Vec3 positionAt(const Trajectory& tr, double t) {
  const auto& s = tr.states;
  const double x = std::clamp(t * tr.rate_hz, 0.0, static_cast<double>(s.size() - 1));
  const auto k = static_cast<std::size_t>(std::floor(x));
  const std::size_t k1 = std::min(k + 1, s.size() - 1);
  const double w = x - static_cast<double>(k);
  return (1.0 - w) * s[k].position_ned_m + w * s[k1].position_ned_m;
}

struct Window {
  double begin_s;
  double end_s;
};

}  // namespace

std::vector<GpsEpoch> simulateGps(const Scenario& scenario, const Trajectory& trajectory, const LocalFrame& frame,
                                  double gps_rate_hz, Rng rng, const GpsReceiverParams& p) {
  std::vector<GpsEpoch> epochs;
  if (trajectory.states.empty() || !(gps_rate_hz > 0.0)) return epochs;
  const double duration = trajectory.states.back().t_s;
  const double dt = 1.0 / gps_rate_hz;

  // Outdoor outages: a Poisson process over the whole run (they only matter outdoors).
  std::vector<Window> outages;
  if (scenario.gps.outage_rate_per_min > 0.0) {
    const double mean_gap = 60.0 / scenario.gps.outage_rate_per_min;
    for (double t = rng.exponential(mean_gap); t < duration; t += rng.exponential(mean_gap)) {
      const double length = rng.uniform(p.outage_min_s, p.outage_max_s);
      outages.push_back({t, t + length});
      t += length;
    }
  }

  const double phi_pos = std::exp(-dt / p.position_time_s);
  const double phi_vel = std::exp(-dt / p.velocity_time_s);
  const Vec3 pos_sigma(p.horizontal_sigma_m, p.horizontal_sigma_m, p.vertical_sigma_m);
  // Correlated errors start in their stationary distribution.
  Vec3 pos_error = pos_sigma.cwiseProduct(rng.gaussian3());
  Vec3 vel_error = p.velocity_sigma_mps * rng.gaussian3();
  vel_error.z() = 0.0;
  bool blocked_before = false;
  double fix_from_s = 0.0;
  int outlier_left = 0;
  Vec3 outlier_pos = Vec3::Zero(), outlier_vel = Vec3::Zero();
  std::optional<double> last_course;
  double satellites = scenario.gps.satellites;

  for (long j = 0;; ++j) {
    const double t = static_cast<double>(j) * dt;
    if (t > duration + 1e-9) break;
    GpsEpoch e;
    e.t_s = t;
    const Vec3 position = positionAt(trajectory, t);
    // A receiver's velocity is a mean over its measurement interval, not a snapshot: the
    // gait's lateral sway (~1 Hz) would otherwise alias into a slow course wobble at 1 Hz.
    const Vec3 velocity = (position - positionAt(trajectory, t - dt)) / dt;
    e.true_position = frame.toGeodetic(position);
    e.true_speed_mps = std::hypot(velocity.x(), velocity.y());
    e.true_course_deg = e.true_speed_mps > 1e-6 ? courseDeg(velocity.x(), velocity.y()) : 0.0;

    // The same count of draws every epoch, whatever happens, keeps the stream aligned.
    const Vec3 pos_step = rng.gaussian3();
    const Vec3 pos_white = rng.gaussian3();
    const Vec3 vel_step = rng.gaussian3();
    const double outlier_draw = rng.uniform01();
    const double outlier_size = rng.uniform(p.outlier_min_m, p.outlier_max_m);
    const double outlier_dir = rng.uniform(0.0, 2.0 * kPi);
    const double outlier_vsize = rng.uniform(p.outlier_velocity_min_mps, p.outlier_velocity_max_mps);
    const double outlier_vdir = rng.uniform(0.0, 2.0 * kPi);
    const double outlier_len = rng.uniform(0.0, 1.0);
    const double reacquire = rng.uniform(p.reacquire_min_s, p.reacquire_max_s);
    const double sat_step = rng.gaussian();
    const double hdop_noise = rng.gaussian();

    pos_error = phi_pos * pos_error + std::sqrt(1.0 - phi_pos * phi_pos) * pos_sigma.cwiseProduct(pos_step);
    vel_error = phi_vel * vel_error + std::sqrt(1.0 - phi_vel * phi_vel) * p.velocity_sigma_mps * vel_step;
    vel_error.z() = 0.0;
    // Visible satellites wander slowly around the environment's typical number.
    satellites += 0.1 * (scenario.gps.satellites - satellites) + 0.3 * sat_step;

    const bool indoor = scenario.phases[phaseAt(scenario, t).index].indoor;
    const bool in_outage =
        std::any_of(outages.begin(), outages.end(), [t](const Window& w) { return t >= w.begin_s && t < w.end_s; });
    const bool blocked = indoor || in_outage;
    if (blocked_before && !blocked) fix_from_s = t + reacquire;
    blocked_before = blocked;
    e.fix = !blocked && t >= fix_from_s;
    if (!e.fix) {
      outlier_left = 0;
      epochs.push_back(e);
      continue;
    }

    if (outlier_left == 0 && outlier_draw < scenario.gps.outlier_probability) {
      outlier_left = 1 + static_cast<int>(outlier_len * p.outlier_max_epochs);
      outlier_pos = outlier_size * Vec3(std::cos(outlier_dir), std::sin(outlier_dir), 0.0);
      outlier_vel = outlier_vsize * Vec3(std::cos(outlier_vdir), std::sin(outlier_vdir), 0.0);
    }
    e.outlier = outlier_left > 0;
    Vec3 measured_pos = position + pos_error + p.position_white_m * pos_white;
    Vec3 measured_vel = velocity + vel_error;
    if (e.outlier) {
      measured_pos += outlier_pos;
      measured_vel += outlier_vel;
      --outlier_left;
    }
    e.position = frame.toGeodetic(measured_pos);
    const double speed = std::hypot(measured_vel.x(), measured_vel.y());
    if (speed >= p.static_hold_mps) {
      e.speed_mps = speed;
      last_course = courseDeg(measured_vel.x(), measured_vel.y());
    }
    e.course_deg = last_course;
    e.satellites = std::clamp(static_cast<int>(std::lround(satellites)) - (e.outlier ? 2 : 0), 4, 14);
    e.hdop = std::max(0.6, 0.3 + 6.0 / e.satellites + 0.05 * hdop_noise + (e.outlier ? 1.0 : 0.0));
    epochs.push_back(e);
  }
  return epochs;
}

}  // namespace headingd::sim
