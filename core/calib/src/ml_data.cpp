#include "headingd/calib/ml_data.hpp"

#include <cmath>
#include <stdexcept>

namespace headingd::calib {

MlData prepareMlData(std::span<const core::ImuSample> samples, const MlDataOptions& options) {
  if (!(options.field_norm_uT > 0.0) || !std::isfinite(options.field_norm_uT)) {
    throw std::invalid_argument("field_norm_uT must be positive");
  }
  if (!(options.gravity_m_s2 > 0.0) || !std::isfinite(options.gravity_m_s2)) {
    throw std::invalid_argument("gravity_m_s2 must be positive");
  }
  MlData data;
  data.gravity_m_s2 = options.gravity_m_s2;
  data.field_norm_uT = options.field_norm_uT;
  data.initial_average_samples = options.initial_average_samples;
  data.samples.reserve(samples.size());
  bool have_previous = false;
  std::int64_t previous_t_ns = 0;
  for (const core::ImuSample& s : samples) {
    if (!s.gyro_rad_s.allFinite() || !s.accel_m_s2.allFinite()) {
      ++data.dropped_non_finite;
      continue;
    }
    MlSample m;
    m.gyro_rad_s = s.gyro_rad_s;
    m.accel_m_s2 = s.accel_m_s2;
    if (s.has_mag) {
      if (s.mag_uT.allFinite()) {
        m.mag_unit = s.mag_uT / options.field_norm_uT;
        m.has_mag = true;
      } else {
        ++data.mag_non_finite;
      }
    }
    if (have_previous) {
      const double dt = 1e-9 * static_cast<double>(s.t_ns - previous_t_ns);
      if (dt > 0.0 && dt <= options.max_dt_s) {
        m.dt_s = dt;
      } else {
        ++data.time_gaps;
      }
    }
    previous_t_ns = s.t_ns;
    have_previous = true;
    data.samples.push_back(m);
  }
  return data;
}

}  // namespace headingd::calib
