#include "headingd/calib/ml/inclination_ekf.hpp"

#include "headingd/calib/ml/ml_likelihood.hpp"

namespace headingd::calib {

std::vector<core::Vec3> verticalInBody(const MlData& data, const InclinationEkfSettings& settings) {
  std::vector<core::Vec3> vertical;
  if (data.samples.empty()) return vertical;
  vertical.reserve(data.samples.size());
  MlModel<double> model;
  model.gyro_bias = settings.gyro_bias_rad_s;
  model.gyro_cov = settings.gyro_cov;
  model.accel_cov = settings.accel_cov;
  MlEkf<double> ekf(model, data.gravity_m_s2);
  core::Vec3 accel0, mag0;
  bool have_mag0 = false;
  initialMeans(data, accel0, mag0, have_mag0);
  // Heading is free here: a large σ would only slow the tilt's first steps, so the usual one.
  ekf.initialiseFromGravity(accel0, kMlInitialAttitudeSigma_rad);
  for (const MlSample& s : data.samples) {
    ekf.predict(s.gyro_rad_s, s.dt_s, s.gyro_noise_dt2_s2);
    if (s.accel_count > 1) {
      ekf.updateAccelMean(s.accel_m_s2, s.accel_mean_rotation, s.accel_count);
    } else {
      ekf.updateAccel(s.accel_m_s2);
    }
    vertical.push_back(ekf.attitude().conjugate() * core::Vec3::UnitZ());
  }
  return vertical;
}

}  // namespace headingd::calib
