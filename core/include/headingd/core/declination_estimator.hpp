#pragma once
// Declination from GPS course against magnetic heading (Henriksson ch. 5).
//
// Each accepted GPS epoch j contributes course θ_GPS(j) minus the sensor's magnetic heading
// ψ_m(j). Epochs are grouped by walking direction; eq. 5.2 averages within a direction,
// eq. 5.1 over the directions (so that an error that depends on direction, e.g. a residual
// hard-iron offset, averages out rather than weighting the most-walked direction). Both
// means are circular (circular_mean.hpp). The difference is declination minus the IMU's
// mounting yaw; the caller adds the mounting yaw (gait_mount_yaw.hpp). The standard error of
// each direction's mean counts consecutive epochs as correlated (Direction::standardError):
// a receiver's course error lasts seconds, so 50 epochs are worth about a dozen.
#include <cstddef>
#include <optional>
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

  // follows_previous: the previous GPS epoch was added too (consecutive epochs are
  // correlated: the receiver's velocity error lasts a few seconds).
  void add(double course_rad, double magnetic_heading_rad, bool follows_previous);

  // Eq. 5.1 over the directions with enough epochs; false before the first such direction.
  bool estimate(AngleEstimate* out) const;
  int directions() const;  // directions with enough epochs
  std::size_t epochs() const { return epochs_; }

 private:
  struct Direction {
    CircularMean course;
    CircularMean difference;  // eq. 5.2
    // For the standard error: the differences about the first one, and their products with
    // the one before for consecutive epochs (lag-1 autocorrelation).
    double reference_rad = 0.0;
    double sum = 0.0, sum_squares = 0.0;
    double lag_products = 0.0, lag_sum_current = 0.0, lag_sum_previous = 0.0;
    std::size_t lag_pairs = 0;
    std::optional<double> previous;  // deviation of the previous epoch, if it was added here
    double standardError() const;
  };
  double direction_width_rad_;
  int min_direction_epochs_;
  std::vector<Direction> directions_;
  std::size_t epochs_ = 0;
  std::optional<std::size_t> last_direction_;  // where the previous epoch went
};

// Inverse-variance mean of independent estimates of one angle (taken about the first, so
// that estimates on either side of ±180° combine correctly).
AngleEstimate fuseAngles(std::span<const AngleEstimate> estimates);

}  // namespace headingd::core
