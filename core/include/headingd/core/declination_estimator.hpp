#pragma once
// Declination from GPS course against magnetic heading (Henriksson ch. 5).
//
// Each accepted GPS epoch j contributes course θ_GPS(j) minus the sensor's magnetic heading
// ψ_m(j). Epochs are grouped by walking direction; eq. 5.2 averages within a direction,
// eq. 5.1 over the directions (so that an error that depends on direction, e.g. a residual
// hard-iron offset, averages out rather than weighting the most-walked direction). Both
// means are circular (circular_mean.hpp). The difference is declination minus the IMU's
// mounting yaw; the caller adds the mounting yaw (gait_mount_yaw.hpp).
#include <span>
#include <vector>

#include "headingd/core/circular_mean.hpp"

namespace headingd::core {

struct AngleEstimate {
  double value_rad = 0.0;
  double sigma_rad = 0.0;
};

class CourseMinusHeading {
 public:
  CourseMinusHeading(double direction_width_rad, int min_direction_epochs)
      : direction_width_rad_(direction_width_rad), min_direction_epochs_(min_direction_epochs) {}

  void add(double course_rad, double magnetic_heading_rad);

  // Eq. 5.1 over the directions with enough epochs; false before the first such direction.
  bool estimate(AngleEstimate* out) const;
  int directions() const;  // directions with enough epochs
  std::size_t epochs() const { return epochs_; }

 private:
  struct Direction {
    CircularMean course;
    CircularMean difference;  // eq. 5.2
  };
  double direction_width_rad_;
  int min_direction_epochs_;
  std::vector<Direction> directions_;
  std::size_t epochs_ = 0;
};

// Inverse-variance mean of independent estimates of one angle (taken about the first, so
// that estimates on either side of ±180° combine correctly).
AngleEstimate fuseAngles(std::span<const AngleEstimate> estimates);

}  // namespace headingd::core
