#include "headingd/calib/ml/ml_data.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

namespace headingd::calib {

namespace {

// Groups of `factor` consecutive samples become one (MlDataOptions::decimation). A sample
// without a prediction (the first, one after a gap) stays alone: nothing is integrated across.
std::vector<MlSample> decimated(const std::vector<MlSample>& samples, std::size_t factor) {
  using core::Mat3;
  using core::Quat;
  using core::Vec3;
  std::vector<MlSample> out;
  out.reserve(samples.size() / factor + 2);
  std::vector<const MlSample*> group;
  group.reserve(factor);
  const auto flush = [&] {
    if (group.empty()) return;
    // Walking back from the group's last sample: R_i maps the body at the group's end to the
    // body at sample i (R_bn,i = R_i R_bn,end), the product of the later increments.
    MlSample m = *group.back();
    Quat to_end = Quat::Identity();  // body(i) → body(end) as q_end = q_i ⊗ to_end
    Vec3 accel_sum = Vec3::Zero(), mag_sum = Vec3::Zero();
    Mat3 accel_rot = Mat3::Zero(), mag_rot = Mat3::Zero();
    double dt_sum = 0.0, dt2_sum = 0.0;
    int mags = 0;
    for (std::size_t k = group.size(); k-- > 0;) {
      const MlSample& s = *group[k];
      const Mat3 r_i = to_end.toRotationMatrix();  // R_bn,i = R(to_end) R_bn,end
      accel_sum += s.accel_m_s2;
      accel_rot += r_i;
      if (s.has_mag) {
        mag_sum += s.mag_unit;
        mag_rot += r_i;
        ++mags;
      }
      const double angle = s.gyro_rad_s.norm() * s.dt_s;
      if (angle > 0.0) to_end = Quat(Eigen::AngleAxisd(angle, s.gyro_rad_s.normalized())) * to_end;
      dt_sum += s.dt_s;
      dt2_sum += s.dt_s * s.dt_s;
    }
    const double n = static_cast<double>(group.size());
    m.dt_s = dt_sum;
    m.gyro_noise_dt2_s2 = dt2_sum;
    const Eigen::AngleAxisd increment(to_end.normalized());
    m.gyro_rad_s = increment.axis() * (increment.angle() / dt_sum);
    m.accel_m_s2 = accel_sum / n;
    m.accel_mean_rotation = accel_rot / n;
    m.accel_count = n;
    m.has_mag = mags > 0;
    if (m.has_mag) {
      m.mag_unit = mag_sum / mags;
      m.mag_mean_rotation = mag_rot / mags;
      m.mag_count = mags;
    }
    out.push_back(m);
    group.clear();
  };
  for (const MlSample& s : samples) {
    if (!(s.dt_s > 0.0)) {
      flush();
      out.push_back(s);
      continue;
    }
    group.push_back(&s);
    if (group.size() == factor) flush();
  }
  flush();
  return out;
}

}  // namespace

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
  data.expected_dip_sign = options.expected_dip_sign;
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
        m.gyro_noise_dt2_s2 = dt * dt;
      } else {
        ++data.time_gaps;
      }
    }
    previous_t_ns = s.t_ns;
    have_previous = true;
    data.samples.push_back(m);
  }
  if (options.decimation > 1) data.samples = decimated(data.samples, options.decimation);
  return data;
}

}  // namespace headingd::calib
