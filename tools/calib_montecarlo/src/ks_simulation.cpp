#include "headingd/calib_montecarlo/ks_simulation.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "headingd/core/angles.hpp"
#include "headingd/sim/imu_model.hpp"
#include "headingd/sim/rng.hpp"

namespace headingd::calib_montecarlo {

namespace {

using core::Mat3;
using core::Quat;
using core::Vec3;

constexpr double kPi = std::numbers::pi;
using core::kRadPerDeg;
constexpr double kRateHz = 100.0;

// A ramp 0 → 1 over s ∈ [0, 1] with zero rate at both ends: the turn starts and ends at rest.
double smoothRamp(double s) { return s - std::sin(2.0 * kPi * s) / (2.0 * kPi); }

// Attitude during the rotation phase, s ∈ [0, 1] of it: turns about body x, y and z at once.
Quat rotationAttitude(KsVariant v, double s) {
  const double turns = v == KsVariant::kShort ? 1.0 : v == KsVariant::kLong ? 3.0 : 20.0;
  const double nods = v == KsVariant::kShort ? 1.0 : v == KsVariant::kLong ? 4.0 : 25.0;
  const double roll = 2.0 * kPi * turns * smoothRamp(s);
  const double pitch = 0.5 * kPi * std::sin(2.0 * kPi * nods * s);
  const double yaw = 2.0 * kPi * (turns + 1.0) * smoothRamp(s);
  return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
              Eigen::AngleAxisd(roll, Vec3::UnitX()));
}

// Table 2's U(lo, hi) per axis, as a σ: the square root of a variance, or the value itself.
Vec3 sigmaFromTable(sim::Rng& rng, double lo, double hi, bool as_sigma) {
  Vec3 v(rng.uniform(lo, hi), rng.uniform(lo, hi), rng.uniform(lo, hi));
  return as_sigma ? v : Vec3(v.cwiseSqrt());
}

}  // namespace

KsVariant parseVariant(std::string_view name) {
  if (name == "short") return KsVariant::kShort;
  if (name == "long") return KsVariant::kLong;
  if (name == "5min") return KsVariant::kFiveMinutes;
  throw std::invalid_argument("unknown variant '" + std::string(name) + "' (short, long, 5min)");
}

const char* variantName(KsVariant v) {
  return v == KsVariant::kShort ? "short" : v == KsVariant::kLong ? "long" : "5min";
}

KsRun simulateKokSchonRun(KsVariant variant, std::uint64_t seed, KsNoiseScale noise) {
  KsRun run;
  const double field = kLinkopingFieldNorm_uT;
  const double dip = kLinkopingDip_deg * kRadPerDeg;
  const Vec3 field_ned = field * Vec3(std::cos(dip), 0.0, std::sin(dip));
  const Vec3 gravity_ned(0.0, 0.0, kGravity_m_s2);
  run.truth.field_norm_uT = field;
  run.truth.dip_rad = dip;

  sim::Rng draw = sim::Rng::stream(seed, 1);
  // Table 2 noise variances (rad/s)², (m/s²)², and (field norm)² for the magnetometer.
  sim::TriadErrorParams gyro, accel, mag;
  const bool as_sigma = noise.table_values_are_sigmas;
  gyro.noise_sigma = noise.factor * sigmaFromTable(draw, 1e-3, 1e-2, as_sigma);
  accel.noise_sigma = noise.factor * sigmaFromTable(draw, 1e-3, 1e-1, as_sigma);
  mag.noise_sigma = noise.factor * field * sigmaFromTable(draw, 1e-3, 1e-1, as_sigma);
  // δω ~ U(-1, 1) per axis, read as °/s as the simulator's consumer grade does.
  gyro.offset_half_width = Vec3::Constant(1.0 * kRadPerDeg);
  // D_diag ~ U(0.5, 1.5), ζ, η, ρ ~ U(-30°, 30°), ψ, θ, φ ~ U(-10°, 10°), o ~ U(-1, 1)·F.
  mag.scale_half_width = 0.5;
  mag.skew_half_width_rad = 30.0 * kRadPerDeg;
  mag.rotation_half_width_rad = 10.0 * kRadPerDeg;
  mag.offset_half_width = Vec3::Constant(field);
  sim::TriadSensor gyro_sensor(gyro, kRateHz, sim::Rng::stream(seed, 2));
  sim::TriadSensor accel_sensor(accel, kRateHz, sim::Rng::stream(seed, 3));
  sim::TriadSensor mag_sensor(mag, kRateHz, sim::Rng::stream(seed, 4));
  run.truth.mag_D = mag_sensor.distortion();
  run.truth.mag_offset_uT = mag_sensor.offset();
  run.truth.gyro_bias_rad_s = gyro_sensor.offset();
  run.truth.gyro_sigma = gyro_sensor.whiteSigma();
  run.truth.accel_sigma = accel_sensor.whiteSigma();
  run.truth.mag_sigma_uT = mag_sensor.whiteSigma();

  // Where the sensor rests: any heading, tilted a little (a hand, a table).
  sim::Rng pose = sim::Rng::stream(seed, 5);
  const Quat q_start(Eigen::AngleAxisd(pose.uniform(-kPi, kPi), Vec3::UnitZ()) *
                     Eigen::AngleAxisd(pose.uniform(-10.0, 10.0) * kRadPerDeg, Vec3::UnitY()) *
                     Eigen::AngleAxisd(pose.uniform(-10.0, 10.0) * kRadPerDeg, Vec3::UnitX()));

  const std::size_t still = 100;
  const std::size_t rotating = variant == KsVariant::kShort ? 300 : variant == KsVariant::kLong ? 2900 : 29900;
  run.stationary_samples = still;
  const std::size_t n = still + rotating;
  run.samples.reserve(n);
  run.q_nb.reserve(n);
  run.mag_noise_free_uT.reserve(n);
  Quat q_prev = q_start;
  for (std::size_t k = 0; k < n; ++k) {
    Quat q = q_start;
    if (k >= still) {
      const double s = static_cast<double>(k - still + 1) / static_cast<double>(rotating);
      q = q_start * rotationAttitude(variant, s);
    }
    core::ImuSample sample;
    sample.t_ns = static_cast<std::int64_t>(k) * 10'000'000;
    // Rate over (t - dt, t]: the rotation from the previous attitude (exact inverse of the
    // quaternion integration the EKF does).
    sample.gyro_rad_s = gyro_sensor.measure(sim::rateBetween(q_prev, q, 1.0 / kRateHz));
    const Mat3 r_bn = q.conjugate().toRotationMatrix();
    sample.accel_m_s2 = accel_sensor.measure(-(r_bn * gravity_ned));  // eq. 16, a = 0
    const Vec3 m_b = r_bn * field_ned;
    sample.mag_uT = mag_sensor.measure(m_b);  // eq. 13
    sample.has_mag = true;
    run.samples.push_back(sample);
    run.q_nb.push_back(q);
    run.mag_noise_free_uT.push_back(run.truth.mag_D * m_b + run.truth.mag_offset_uT);
    q_prev = q;
  }
  return run;
}

double headingRmseRad(const KsRun& run, const Mat3& D, const Vec3& offset_uT) {
  const Mat3 d_inv = D.inverse();
  double sum = 0.0;
  for (std::size_t k = 0; k < run.q_nb.size(); ++k) {
    const Vec3 m_b = d_inv * (run.mag_noise_free_uT[k] - offset_uT);
    // Levelling m_b with the true roll and pitch gives Rz(-ψ) R_nb m_b, whose heading
    // -atan2(east, north) is the compass heading ψ̂; ψ̂ - ψ is then minus the azimuth of the
    // calibrated field turned into NED with the true attitude (x is magnetic north).
    const Vec3 m_n = run.q_nb[k] * m_b;
    const double err = -std::atan2(m_n.y(), m_n.x());
    sum += err * err;
  }
  return std::sqrt(sum / static_cast<double>(run.q_nb.size()));
}

}  // namespace headingd::calib_montecarlo
