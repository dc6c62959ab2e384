#include "headingd/core/mag_heading_observer.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::core {
namespace {

// atan2(y, x). Once the heading is aligned, the field's horizontal direction is within a
// degree or two of north (y ≪ x): there atan(y/x) by its series to t¹¹ is exact to rounding
// (the first term left out is below 7e-20 of the result) and costs a fraction of std::atan2.
double headingOffsetAngle(double y, double x) {
  if (x > 0.0 && std::abs(y) < 0.03125 * x) {
    const double t = y / x, t2 = t * t;
    return t * (1.0 + t2 * (-1.0 / 3.0 + t2 * (1.0 / 5.0 + t2 * (-1.0 / 7.0 + t2 * (1.0 / 9.0 + t2 * (-1.0 / 11.0))))));
  }
  return std::atan2(y, x);
}

}  // namespace

MagHeadingMeasurement measureMagHeading(const Quat& q_nb, const Vec3& mag_uT, double min_horizontal_fraction) {
  MagHeadingMeasurement m;
  const Vec3 field_n = q_nb * mag_uT;
  // The fraction test on squares: one square root fewer per sample.
  const double horizontal2 = field_n.head<2>().squaredNorm();
  const double total2 = horizontal2 + field_n.z() * field_n.z();
  m.horizontal_uT = std::sqrt(horizontal2);
  const double min_fraction = std::max(min_horizontal_fraction, 0.0);
  if (!(total2 > 0.0) || horizontal2 < min_fraction * min_fraction * total2) return m;
  m.dip_rad = std::atan2(field_n.z(), m.horizontal_uT);
  m.innovation_rad = -headingOffsetAngle(field_n.y(), field_n.x());
  m.valid = true;
  return m;
}

double measuredHeading(const Quat& q_nb, const MagHeadingMeasurement& m) {
  return wrapAngle(yawZyx(q_nb) + m.innovation_rad);
}

double magObserverGain(double dt_s, double time_constant_s) {
  const double x = dt_s / time_constant_s;
  // 1 - exp(-x); the series is exact to 1e-12 for the small x of every sample.
  if (x < 0.01) return x * (1.0 - 0.5 * x * (1.0 - x / 3.0 * (1.0 - 0.25 * x)));
  return -std::expm1(-x);
}

Quat applyHeadingCorrection(const Quat& q_nb, double innovation_rad, double gain) {
  return (headingRotation(gain * innovation_rad) * q_nb).normalized();
}

}  // namespace headingd::core
