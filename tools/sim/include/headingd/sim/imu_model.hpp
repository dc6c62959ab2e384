#pragma once
// Sensor error models of the IMU's three triads, each
//     y = D x + o + b(t) + n
// in sensor axes: x the true signal, D = D_diag D_skew D_rot the scale factors,
// non-orthogonality and misalignment (Kok & Schön 2016 eq. 31-32), o a constant offset,
// b(t) a bias that drifts (random walk plus a first-order Gauss-Markov process, MAGYQ §3.2),
// n white noise. The defaults and their sources are in imu_model.cpp.
#include <string_view>

#include "headingd/core/quaternion.hpp"
#include "headingd/sim/rng.hpp"

namespace headingd::sim {

struct TriadErrorParams {
  core::Vec3 noise_density = core::Vec3::Zero();      // white noise, unit/√Hz: σ = density·√rate
  core::Vec3 noise_sigma = core::Vec3::Zero();        // white noise per sample, unit (added in quadrature)
  core::Vec3 offset_half_width = core::Vec3::Zero();  // o ~ U(-h, h) per axis
  core::Vec3 offset_drawn = core::Vec3::Zero();       // plus this, drawn elsewhere (the phone grade's)
  core::Vec3 bias_walk_density = core::Vec3::Zero();  // random walk, unit/√s
  core::Vec3 markov_sigma = core::Vec3::Zero();       // Gauss-Markov stationary σ, unit
  core::Vec3 markov_time_s = core::Vec3::Ones();      // its correlation time
  double scale_half_width = 0.0;                      // D_ii = 1 + U(-h, h)
  double skew_half_width_rad = 0.0;                   // ζ, η, ρ of D_skew ~ U(-h, h)
  double rotation_half_width_rad = 0.0;               // zyx angles of D_rot ~ U(-h, h)
  double full_scale = 0.0;  // each axis reads at most ±this (the sensor saturates); 0: no limit
};

// ideal: no errors at all. consumer: a calibrated consumer-grade MEMS IMU (the default), with
// the noise and bias instability of a 2014 smartphone (MAGYQ's tables; its gyro is ~15 times
// noisier than a current part). mems: consumer, with the white noise of current consumer
// 9-axis parts' datasheets and their gyros' bias instability. uncalibrated: consumer, but the magnetometer distorted as
// in Kok & Schön's Monte Carlo study (soft and hard iron of a raw sensor), for the calibration tools. phone: a phone's
// sensors drawn per seed from ranges (phone_imu.hpp): noisy gyro with a constant bias up to 6 deg/s, and a magnetometer
// slower than the IMU and late against the gyro.
enum class ImuGrade { kIdeal, kConsumer, kUncalibrated, kMems, kPhone };
const char* imuGradeName(ImuGrade g);
// Throws std::invalid_argument for an unknown name.
ImuGrade parseImuGrade(std::string_view name);

struct ImuErrorParams {
  TriadErrorParams gyro;   // rad/s
  TriadErrorParams accel;  // m/s²
  TriadErrorParams mag;    // µT
};
// Magnetometer errors scale with the field strength (Kok & Schön normalise the field to 1).
// The fixed grades only: throws std::invalid_argument for kPhone, whose errors are drawn
// (imuModel).
ImuErrorParams imuErrorParams(ImuGrade grade, double field_strength_uT);

// When the accelerometer and magnetometer sample against the gyro's rows. A lagging triad's
// row describes the motion as it was `lag` earlier; a slower magnetometer takes a new sample
// at first + j / rate (its own clock) and its last sample is repeated in every row until the
// next, as phones' sensor APIs deliver it.
struct SensorTiming {
  double mag_rate_hz = 0.0;         // 0: a new magnetometer sample with every row
  double mag_first_sample_s = 0.0;  // time of magnetometer sample 0, within [0, 1/rate)
  double mag_lag_s = 0.0;
  double accel_lag_s = 0.0;
  bool isDefault() const { return mag_rate_hz == 0.0 && mag_lag_s == 0.0 && accel_lag_s == 0.0; }
};

struct ImuModel {
  ImuErrorParams errors;
  SensorTiming timing;
};
// The consumer grade's triads (the phone grade starts from them).
TriadErrorParams consumerGyroErrors();
TriadErrorParams consumerAccelErrors();
TriadErrorParams consumerMagErrors(double field_strength_uT);

// The grade's errors and timing. The phone grade draws them from `rng`; the others are fixed
// (and draw nothing).
ImuModel imuModel(ImuGrade grade, double field_strength_uT, Rng rng);

// One triad: draws D and o at construction, then advances its bias once per measure().
class TriadSensor {
 public:
  TriadSensor(const TriadErrorParams& params, double rate_hz, Rng rng);
  core::Vec3 measure(const core::Vec3& truth);

  const core::Mat3& distortion() const { return d_; }
  const core::Vec3& offset() const { return offset_; }
  core::Vec3 driftingBias() const { return walk_ + markov_; }
  const core::Vec3& whiteSigma() const { return white_sigma_; }
  double fullScale() const { return p_.full_scale; }

 private:
  TriadErrorParams p_;
  double dt_s_;
  Rng rng_;
  core::Mat3 d_;
  core::Vec3 offset_;
  core::Vec3 white_sigma_;
  core::Vec3 walk_ = core::Vec3::Zero();
  core::Vec3 markov_;
};

// The constant body rate that turns q_from into q_to in dt: ω with
// q_to = q_from ⊗ exp(½ ω dt), exactly the inverse of core::gyroIncrement.
core::Vec3 rateBetween(const core::Quat& q_from, const core::Quat& q_to, double dt_s);

}  // namespace headingd::sim
