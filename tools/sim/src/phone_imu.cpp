#include "headingd/sim/phone_imu.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace headingd::sim {

namespace {

using core::Vec3;

double logUniform(Rng& rng, const DrawRange& r) { return std::exp(rng.uniform(std::log(r.lo), std::log(r.hi))); }
double uniform(Rng& rng, const DrawRange& r) { return rng.uniform(r.lo, r.hi); }

}  // namespace

// Sources:
//   [issue 28] the held-out consumer IMU and phone recordings: gyro rest noise 0.010-0.014
//           rad/s per sample at 100 Hz on the consumer IMU, constant biases up to 6 deg/s,
//           phone magnetometers at 25-50 Hz repeated between updates and 20-40 ms late.
//   [datasheets] phone accelerometers: BMI160 180 µg/√Hz, LSM6DSL 90-130, older parts up to
//           400; phone magnetometers (AK09911/AK09915/AK8963): 0.15-0.6 µT resolution, 0.3-0.6
//           µT RMS noise, more with the phone's own fields.
//   [consumer] the consumer grade (imu_model.cpp), a 2014 smartphone (MAGYQ's tables).
//   [shared phones] ../shared/data/phones: the Nexus 5's and iPhone 4S's accelerometers read
//           at most ±2 g (19.5-20.1 m/s², values piled up there while running), the iPhone
//           5's up to 45 m/s².
// Log-uniform where the range spans a factor of several, so each decade is as likely.
ImuModel drawPhoneImu(double field_strength_uT, Rng& rng) {
  ImuModel m;
  TriadErrorParams& gyro = m.errors.gyro;
  gyro = consumerGyroErrors();  // [consumer] drifting bias, scale, skew, rotation
  gyro.noise_density = Vec3::Constant(logUniform(rng, PhoneRanges::kGyroNoiseAt100Hz_rad_s) / std::sqrt(100.0));
  gyro.offset_half_width = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {  // [issue 28] up to 6 deg/s, either sign
    const double sign = rng.uniform01() < 0.5 ? -1.0 : 1.0;
    gyro.offset_drawn(i) = sign * logUniform(rng, PhoneRanges::kGyroBiasMagnitude_rad_s);
  }
  TriadErrorParams& accel = m.errors.accel;
  accel = consumerAccelErrors();  // [consumer] drifting bias, scale, skew, rotation
  accel.noise_density = Vec3::Constant(logUniform(rng, PhoneRanges::kAccelNoiseDensity));  // [datasheets]
  accel.offset_half_width = Vec3::Constant(0.05);  // [ours] ±5 mg left after the phone's factory trim
  TriadErrorParams& mag = m.errors.mag;
  mag = consumerMagErrors(field_strength_uT);  // [consumer] ~1 µT residual hard iron, soft iron
  mag.noise_sigma = Vec3::Constant(uniform(rng, PhoneRanges::kMagNoise_uT));  // [datasheets]
  SensorTiming& t = m.timing;                                                 // [issue 28]
  t.mag_rate_hz = uniform(rng, PhoneRanges::kMagRate_hz);
  t.mag_first_sample_s = rng.uniform(0.0, 1.0 / t.mag_rate_hz);  // the two clocks' phase
  t.mag_lag_s = uniform(rng, PhoneRanges::kMagLag_s);
  t.accel_lag_s = uniform(rng, PhoneRanges::kAccelLag_s);  // "a few ms"
  // Drawn last, so that every earlier draw (and every run without clipping) is as it was.
  const auto& scales = PhoneRanges::kAccelFullScale_m_s2;
  const auto pick = static_cast<std::size_t>(rng.uniform01() * static_cast<double>(std::size(scales)));
  accel.full_scale = scales[std::min(pick, std::size(scales) - 1)];  // [shared phones]
  return m;
}

}  // namespace headingd::sim
