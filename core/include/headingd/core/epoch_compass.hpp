#pragma once
// The sensor's mean magnetic heading over one GPS epoch interval, from the mean
// magnetometer vector of that interval (a tilt-compensated compass, Henriksson eqs. 2.31
// and 4.1, on means instead of single samples).
//
// Mean over the interval, not the heading at its end: the receiver's velocity, and so its
// course, is a mean over the interval too, and a walking trunk yaws by a few degrees at the
// stride rate (~0.95 Hz). Sampled once a second, the end heading carried that yaw as a slow
// ±3° wave (the alias of 0.95 Hz at 1 Hz) that the course does not have.
//
// Why not the attitude estimator's heading: declination from GPS course (Henriksson ch. 5)
// compares the course with the heading at each epoch, and what matters is the error common
// to many epochs. The filtered heading carries slow errors: gyro noise integrated in the
// tilt (a tilt error δ turns into a heading error of about δ·tan(dip), three times δ in
// Stockholm) and in the heading between magnetometer corrections. Over one epoch these means
// have neither: the gyro only carries the vectors across one second (its noise over one
// second is tiny), and what remains is white from epoch to epoch and averages out over the
// walk. A walker's accelerations average to nearly zero over the ~2 steps of one epoch;
// what does not is fixed in the body, turns with the walking direction and cancels between
// directions (eq. 5.1).
//
// The vectors are summed in the gyro frame of the interval's start (rotated there by the
// bias-corrected gyro, as in gyro_frame_low_pass.hpp) and the means rotated back into the
// sensor axes of the interval's end; the heading of those axes is then moved to the mean of
// the sensor's x-axis over the interval (carried in the same gyro frame).
#include <cstddef>
#include <optional>

#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class EpochCompass {
 public:
  // Every accepted IMU sample: the gyro (bias removed) moves the frame; the field counts
  // only when the sample has one.
  void add(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, const Vec3* mag_uT, double dt_s);

  // At a GPS epoch: the sensor's mean heading from magnetic north over the interval since the
  // last call, if it had at least min_samples samples (at least one with a field: a magnetometer
  // may be slower than the gyro) and a usable horizontal field; then starts the next interval.
  std::optional<double> takeHeading(std::size_t min_samples, double min_horizontal_fraction);

  // Forget the interval (after a gap in the samples: the gyro frame is not valid across it).
  void restart();

  Quat q_start_sensor_ = Quat::Identity();  // the current sensor axes in the start frame
  Vec3 accel_sum_ = Vec3::Zero();
  Vec3 mag_sum_ = Vec3::Zero();
  Vec3 x_axis_sum_ = Vec3::Zero();  // the sensor's x-axis, start frame
  std::size_t accel_count_ = 0;
  std::size_t mag_count_ = 0;
};

}  // namespace headingd::core
