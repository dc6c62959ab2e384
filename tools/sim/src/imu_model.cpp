#include "headingd/sim/imu_model.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "headingd/core/angles.hpp"
#include "headingd/sim/phone_imu.hpp"

namespace headingd::sim {

namespace {

using core::Mat3;
using core::Vec3;

using core::kRadPerDeg;
constexpr double kMilliG = 9.80665e-3;  // m/s² per mg

// Sources of the defaults:
//   [K&S]   M. Kok, T. B. Schön, "Magnetometer calibration using inertial sensors", IEEE
//           Sensors J. 16(14), 2016, Table 2 (Monte Carlo settings, uniform distributions).
//   [MAGYQ] V. Renaudin, C. Combettes, "MAGYQ-based attitude estimation with smartphone
//           sensors for indoor pedestrian navigation", Sensors 14, 2014, Table 1
//           (accelerometer) and Table 2 (gyroscope), Allan-variance figures of a smartphone.
//   [ours]  neither paper gives the figure for a calibrated sensor; a typical residual after
//           a six-position / multi-pose calibration (Henriksson 2013 §2.8).
TriadErrorParams consumerGyro() {
  TriadErrorParams p;
  // [MAGYQ] Table 2 angular random walk, X/Y/Z, rad/s/√Hz: 0.041 rad/s per sample at 100 Hz,
  // inside [K&S]'s Σω ~ U(1e-3, 1e-2) (rad/s)².
  p.noise_density = Vec3(0.00413, 0.00445, 0.00442);
  // [MAGYQ] Table 2 bias instability, rad/s, as a Gauss-Markov σ; its correlation time
  // (30 s, [ours]) puts the Allan-deviation floor where the table's figures place it.
  p.markov_sigma = Vec3(0.00117, 0.00121, 0.00105);
  p.markov_time_s = Vec3::Constant(30.0);
  // [MAGYQ] Table 2 rate random walk 0.00158/0.00142/0.00157, read per √h (the usual unit
  // of RRW; per √s the Allan curve would have no bias-instability floor at all).
  p.bias_walk_density = Vec3(0.00158, 0.00142, 0.00157) / 60.0;
  // [K&S] δω ~ U(-1, 1) per axis; the table prints no unit, read as °/s.
  p.offset_half_width = Vec3::Constant(1.0 * kRadPerDeg);
  p.scale_half_width = 0.005;                    // [ours] ±0.5 %
  p.skew_half_width_rad = 0.2 * kRadPerDeg;      // [ours]
  p.rotation_half_width_rad = 0.2 * kRadPerDeg;  // [ours]
  return p;
}

TriadErrorParams consumerAccel() {
  TriadErrorParams p;
  // [MAGYQ] Table 1 velocity random walk, X/Y/Z, mg/√Hz (6.4e-3 m/s² per sample at 100 Hz).
  p.noise_density = Vec3(0.0650, 0.0717, 0.0639) * kMilliG;
  // [MAGYQ] Table 1 correlated noise (mg) and correlation time (s): the Gauss-Markov bias
  // of their accelerometer model, b' = -b/τ + n.
  p.markov_sigma = Vec3(0.1484, 0.0373, 0.0881) * kMilliG;
  p.markov_time_s = Vec3(18.16, 48.05, 197.2);
  p.offset_half_width = Vec3::Constant(0.02);    // [ours] ±2 mg residual offset
  p.scale_half_width = 0.005;                    // [ours]
  p.skew_half_width_rad = 0.2 * kRadPerDeg;      // [ours]
  p.rotation_half_width_rad = 0.2 * kRadPerDeg;  // [ours]
  return p;
}

TriadErrorParams consumerMag(double field_uT) {
  TriadErrorParams p;
  // [K&S] Σm ~ U(1e-3, 1e-1) for a field of norm 1: the lower bound, σ = √1e-3·|m|
  // (about 1.6 µT at 51 µT), per sample.
  p.noise_sigma = Vec3::Constant(std::sqrt(1e-3) * field_uT);
  p.offset_half_width = Vec3::Constant(0.02 * field_uT);  // [ours] residual hard iron, ~1 µT
  p.scale_half_width = 0.005;                             // [ours] residual soft iron
  p.skew_half_width_rad = 0.2 * kRadPerDeg;               // [ours]
  p.rotation_half_width_rad = 0.5 * kRadPerDeg;           // [ours] magnetometer to IMU axes
  return p;
}

// [datasheets] white noise of current consumer 9-axis parts: gyroscope 0.015 deg/s/√Hz
// (ICM-20948; BMI270 0.007), accelerometer 200 µg/√Hz (ICM-20948 230, BMI270 160),
// magnetometer 0.6 µT RMS per sample (AK09916, BMM150: 0.3-0.6). [ours] the gyro's bias
// instability: 20 deg/h, within the 5-30 deg/h that Allan-deviation measurements of such
// parts give (MAGYQ's 2014 phone: 241 deg/h). Everything else as consumer.
ImuErrorParams memsErrors(double field_uT) {
  ImuErrorParams e{consumerGyro(), consumerAccel(), consumerMag(field_uT)};
  e.gyro.noise_density = Vec3::Constant(0.015 * kRadPerDeg);
  e.gyro.markov_sigma = Vec3::Constant(20.0 / 3600.0 * kRadPerDeg);
  e.accel.noise_density = Vec3::Constant(0.2 * kMilliG);
  e.mag.noise_sigma = Vec3::Constant(0.6);
  return e;
}

TriadErrorParams uncalibratedMag(double field_uT) {
  TriadErrorParams p = consumerMag(field_uT);
  // [K&S] Table 2 as it stands: D_diag ~ U(0.5, 1.5), ζ, η, ρ ~ U(-30°, 30°),
  // ψ, θ, φ ~ U(-10°, 10°), o ~ U(-1, 1) in units of the field norm.
  p.offset_half_width = Vec3::Constant(field_uT);
  p.scale_half_width = 0.5;
  p.skew_half_width_rad = 30.0 * kRadPerDeg;
  p.rotation_half_width_rad = 10.0 * kRadPerDeg;
  return p;
}

// Kok & Schön eq. 32.
Mat3 skewMatrix(double zeta, double eta, double rho) {
  Mat3 m;
  m << 1.0, 0.0, 0.0,                       //
      std::sin(zeta), std::cos(zeta), 0.0,  //
      -std::sin(eta), std::cos(eta) * std::sin(rho), std::cos(eta) * std::cos(rho);
  return m;
}

}  // namespace

const char* imuGradeName(ImuGrade g) {
  switch (g) {
    case ImuGrade::kIdeal: return "ideal";
    case ImuGrade::kConsumer: return "consumer";
    case ImuGrade::kUncalibrated: return "uncalibrated";
    case ImuGrade::kMems: return "mems";
    case ImuGrade::kPhone: return "phone";
  }
  return "unknown";
}

ImuGrade parseImuGrade(std::string_view name) {
  for (const ImuGrade g :
       {ImuGrade::kIdeal, ImuGrade::kConsumer, ImuGrade::kUncalibrated, ImuGrade::kMems, ImuGrade::kPhone}) {
    if (name == imuGradeName(g)) return g;
  }
  throw std::invalid_argument("unknown IMU grade '" + std::string(name) +
                              "' (ideal, consumer, uncalibrated, mems, phone)");
}

ImuErrorParams imuErrorParams(ImuGrade grade, double field_strength_uT) {
  switch (grade) {
    case ImuGrade::kIdeal: return {};
    case ImuGrade::kConsumer: return {consumerGyro(), consumerAccel(), consumerMag(field_strength_uT)};
    case ImuGrade::kUncalibrated: return {consumerGyro(), consumerAccel(), uncalibratedMag(field_strength_uT)};
    case ImuGrade::kMems: return memsErrors(field_strength_uT);
    case ImuGrade::kPhone: break;
  }
  throw std::invalid_argument(std::string("IMU grade '") + imuGradeName(grade) + "' is drawn per seed (imuModel)");
}

ImuModel imuModel(ImuGrade grade, double field_strength_uT, Rng rng) {
  if (grade == ImuGrade::kPhone) return drawPhoneImu(field_strength_uT, rng);
  return {imuErrorParams(grade, field_strength_uT), SensorTiming{}};
}

TriadErrorParams consumerGyroErrors() { return consumerGyro(); }
TriadErrorParams consumerAccelErrors() { return consumerAccel(); }
TriadErrorParams consumerMagErrors(double field_uT) { return consumerMag(field_uT); }

TriadSensor::TriadSensor(const TriadErrorParams& params, double rate_hz, Rng rng)
    : p_(params), dt_s_(1.0 / rate_hz), rng_(rng) {
  // Every number is drawn whatever the parameters, so grades that differ in one triad share
  // the noise of the others (and ideal vs consumer differ only by the errors).
  Vec3 scale;
  for (int i = 0; i < 3; ++i) scale(i) = 1.0 + rng_.uniform(-p_.scale_half_width, p_.scale_half_width);
  const Vec3 skew = rng_.uniform3(p_.skew_half_width_rad);
  const Vec3 rot = rng_.uniform3(p_.rotation_half_width_rad);
  const Mat3 d_rot = (Eigen::AngleAxisd(rot(0), Vec3::UnitZ()) * Eigen::AngleAxisd(rot(1), Vec3::UnitY()) *
                      Eigen::AngleAxisd(rot(2), Vec3::UnitX()))
                         .toRotationMatrix();
  d_ = scale.asDiagonal() * skewMatrix(skew(0), skew(1), skew(2)) * d_rot;  // Kok & Schön eq. 31
  for (int i = 0; i < 3; ++i) {
    offset_(i) = rng_.uniform(-p_.offset_half_width(i), p_.offset_half_width(i)) + p_.offset_drawn(i);
  }
  // The Gauss-Markov bias starts in its stationary distribution.
  markov_ = p_.markov_sigma.cwiseProduct(rng_.gaussian3());
  const double rate = 1.0 / dt_s_;
  white_sigma_ = (p_.noise_density.array().square() * rate + p_.noise_sigma.array().square()).sqrt();
}

Vec3 TriadSensor::measure(const Vec3& truth) {
  const Vec3 walk_step = rng_.gaussian3();
  const Vec3 markov_step = rng_.gaussian3();
  const Vec3 white = rng_.gaussian3();
  Vec3 y = d_ * truth + offset_ + walk_ + markov_ + white_sigma_.cwiseProduct(white);
  if (p_.full_scale > 0.0) y = y.cwiseMax(-p_.full_scale).cwiseMin(p_.full_scale);
  walk_ += std::sqrt(dt_s_) * p_.bias_walk_density.cwiseProduct(walk_step);
  for (int i = 0; i < 3; ++i) {
    // Exact discretisation of b' = -b/τ + w with stationary σ: b ← φ b + σ √(1-φ²) n.
    const double phi = std::exp(-dt_s_ / p_.markov_time_s(i));
    markov_(i) = phi * markov_(i) + p_.markov_sigma(i) * std::sqrt(1.0 - phi * phi) * markov_step(i);
  }
  return y;
}

Vec3 rateBetween(const core::Quat& q_from, const core::Quat& q_to, double dt_s) {
  core::Quat r = q_from.conjugate() * q_to;
  if (r.w() < 0.0) r.coeffs() = -r.coeffs();  // the shorter of the two rotations
  const double s = r.vec().norm();
  const double angle = 2.0 * std::atan2(s, r.w());
  // angle/s → 2 as s → 0 (small-angle limit of 2·atan2(s, w)/s with w → 1).
  const double factor = s > 1e-12 ? angle / s : 2.0 / r.w();
  return (factor / dt_s) * r.vec();
}

}  // namespace headingd::sim
