#pragma once
// A recording in other units parses as well as one in SI and is wrong everywhere: specific
// force in g (|a| about 1), a field in gauss (about 0.5) or nT (about 50 000), angular rate in
// degrees per second. Over the first kWindowS seconds of accepted samples the mean norms are
// compared with what Earth gives: gravity, 9.8 m/s², which a body in motion also averages to
// within a few m/s²; a field of 22-67 µT, 10-200 µT where it is disturbed indoors (suspected
// outside 5-500 µT: gauss gives about 0.5, nT about 50 000). The
// angular rate has no such reference (a body at rest reads its bias, one turning anything), so
// only a mean rate no person reaches (over 20 rad/s, 1150°/s, for seconds: a rate in °/s is 57
// times too large) is suspected. A diagnostic: the estimates do not change; the daemon logs
// it once and STATUS counts it (units_suspect_*), headingd-replay prints it.
#include <cstdint>
#include <string>

#include "headingd/core/imu_sample.hpp"

namespace headingd::core {

class SensorUnitsCheck {
 public:
  static constexpr double kWindowS = 10.0;

  // An accepted sample and the time it stands for.
  void add(const ImuSample& s, double dt_s);

  bool decided() const { return decided_; }
  bool accelSuspect() const { return accel_suspect_; }
  bool gyroSuspect() const { return gyro_suspect_; }
  bool magSuspect() const { return mag_suspect_; }
  // One sentence per suspect sensor, with the mean that gave it away ("" when none).
  std::string describe() const;

 private:
  double seconds_ = 0.0;
  double accel_sum_ = 0.0, gyro_sum_ = 0.0, mag_sum_ = 0.0;
  double mag_seconds_ = 0.0;
  bool decided_ = false;
  bool accel_suspect_ = false, gyro_suspect_ = false, mag_suspect_ = false;
};

}  // namespace headingd::core
