#include "headingd/core/sensor_units_check.hpp"

#include <cstdio>

namespace headingd::core {
namespace {

// Beyond these the mean cannot be Earth's gravity or field in SI units, whatever the motion
// or the disturbance (header).
constexpr double kMinAccelMean = 4.0, kMaxAccelMean = 25.0;  // m/s²
constexpr double kMinMagMean = 5.0, kMaxMagMean = 500.0;     // µT
constexpr double kMaxGyroMean = 20.0;                        // rad/s

}  // namespace

void SensorUnitsCheck::add(const ImuSample& s, double dt_s) {
  if (decided_ || !(dt_s > 0.0)) return;
  seconds_ += dt_s;
  accel_sum_ += s.accel_m_s2.norm() * dt_s;
  gyro_sum_ += s.gyro_rad_s.norm() * dt_s;
  if (s.has_mag) {
    mag_sum_ += s.mag_uT.norm() * dt_s;
    mag_seconds_ += dt_s;
  }
  if (seconds_ < kWindowS) return;
  decided_ = true;
  const double accel = accel_sum_ / seconds_;
  accel_suspect_ = accel < kMinAccelMean || accel > kMaxAccelMean;
  gyro_suspect_ = gyro_sum_ / seconds_ > kMaxGyroMean;
  if (mag_seconds_ >= 0.5 * seconds_) {
    const double mag = mag_sum_ / mag_seconds_;
    mag_suspect_ = mag < kMinMagMean || mag > kMaxMagMean;
  }
}

std::string SensorUnitsCheck::describe() const {
  std::string text;
  char line[240];
  if (accel_suspect_) {
    std::snprintf(line, sizeof line,
                  "the accelerometer's mean norm over the first %.0f s is %.3g, not about 9.8 m/s^2 (in g?); ",
                  seconds_, accel_sum_ / seconds_);
    text += line;
  }
  if (gyro_suspect_) {
    std::snprintf(line, sizeof line,
                  "the gyro's mean rate over the first %.0f s is %.3g rad/s, more than a person turns (in deg/s?); ",
                  seconds_, gyro_sum_ / seconds_);
    text += line;
  }
  if (mag_suspect_) {
    std::snprintf(line, sizeof line,
                  "the magnetometer's mean norm over the first %.0f s is %.3g, outside the 5-500 uT that Earth's field "
                  "gives even near steel (in gauss? nT?); ",
                  seconds_, mag_sum_ / mag_seconds_);
    text += line;
  }
  if (!text.empty()) text.resize(text.size() - 2);
  return text;
}

}  // namespace headingd::core
