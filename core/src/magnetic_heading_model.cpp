#include "headingd/core/magnetic_heading_model.hpp"

#include <cmath>
#include <limits>

namespace headingd::core {

Linearised<1> MagneticHeadingModel::linearise(const NavigationState& x, const Vec3& field_sensor_uT) const {
  const Vec3 m = x.q_nb * field_sensor_uT;
  const double horizontal2 = m.x() * m.x() + m.y() * m.y();
  Linearised<1> l;
  if (!(horizontal2 > min_horizontal_fraction * min_horizontal_fraction * m.squaredNorm())) {
    l.noise_covariance(0, 0) = std::numeric_limits<double>::infinity();
    return l;
  }
  l.residual(0) = -std::atan2(m.y(), m.x());
  const Eigen::RowVector3d azimuth_gradient = Eigen::RowVector3d(-m.y(), m.x(), 0.0) / horizontal2;
  l.jacobian.block<1, 3>(0, error_state::kAttitude) = -azimuth_gradient * crossMatrix(m);
  l.noise_covariance(0, 0) = noise_sigma_rad * noise_sigma_rad;
  return l;
}

}  // namespace headingd::core
