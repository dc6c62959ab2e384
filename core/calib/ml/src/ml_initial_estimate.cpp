#include "headingd/calib/ml/ml_initial_estimate.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <string>
#include <vector>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/calib/ellipsoid_fit.hpp"
#include "headingd/calib/ml/inclination_ekf.hpp"
#include "headingd/calib/ml/misalignment.hpp"
#include "headingd/calib/ml/ml_data.hpp"
#include "headingd/calib/ml/ml_stationary.hpp"

namespace headingd::calib {

namespace {

// The covariance with its eigenvalues raised to at least σ_min².
core::Mat3 withFloor(const core::Mat3& cov, double sigma_min) {
  const Eigen::SelfAdjointEigenSolver<core::Mat3> eig(0.5 * (cov + cov.transpose()));
  const core::Vec3 values = eig.eigenvalues().cwiseMax(sigma_min * sigma_min);
  return eig.eigenvectors() * values.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace

MlInitialEstimate estimateInitialParameters(std::span<const core::ImuSample> samples, const MlInitialOptions& options) {
  if (options.stationary_begin + options.stationary_count > samples.size()) {
    throw CalibrationError("stationary segment [" + std::to_string(options.stationary_begin) + ", " +
                           std::to_string(options.stationary_begin + options.stationary_count) + ") lies outside the " +
                           std::to_string(samples.size()) + " samples");
  }
  MlInitialEstimate out;
  out.field_norm_uT = options.field_norm_uT;

  // Step 1a.
  const StationaryStatistics still =
      stationaryStatistics(samples.subspan(options.stationary_begin, options.stationary_count));
  out.gyro_bias_rad_s = still.gyro_bias_rad_s;
  out.gyro_cov = still.gyro_cov;
  out.accel_cov = still.accel_cov;
  out.mag_cov_uT2 = still.mag_cov_uT2;
  out.gravity_m_s2 = options.gravity_m_s2 > 0.0 ? options.gravity_m_s2 : still.accel_mean_m_s2.norm();

  // Step 1b: all magnetometer readings.
  std::vector<core::Vec3> mag;
  mag.reserve(samples.size());
  for (const core::ImuSample& s : samples) {
    if (s.has_mag && s.mag_uT.allFinite()) mag.push_back(s.mag_uT);
  }
  EllipsoidFitOptions fit_options;
  fit_options.min_coverage = options.ellipsoid_min_coverage;
  fit_options.sphere_weight = options.ellipsoid_sphere_weight;
  const EllipsoidFit fit = fitEllipsoid(mag, options.field_norm_uT, fit_options);
  out.ellipsoid_D = fit.D;
  out.offset_uT = fit.offset_uT;
  out.ellipsoid_coverage = fit.coverage;
  out.ellipsoid_residual_rms_uT = fit.residual_rms_uT;
  out.ellipsoid_condition_number = fit.condition_number;

  // Step 1c: the vertical from the inertial-only EKF, the field on the fitted unit sphere.
  MlDataOptions data_options;
  data_options.field_norm_uT = options.field_norm_uT;
  data_options.gravity_m_s2 = out.gravity_m_s2;
  data_options.initial_average_samples = options.initial_average_samples;
  data_options.expected_dip_sign = options.expected_dip_sign;
  const MlData data = prepareMlData(samples, data_options);
  InclinationEkfSettings ekf;
  ekf.gyro_bias_rad_s = out.gyro_bias_rad_s;
  ekf.gyro_cov = withFloor(out.gyro_cov, options.min_gyro_sigma_rad_s);
  ekf.accel_cov = withFloor(out.accel_cov, options.min_accel_sigma_m_s2);
  const std::vector<core::Vec3> vertical_all = verticalInBody(data, ekf);
  const core::Mat3 d_tilde_inv = fit.D.inverse();
  std::vector<core::Vec3> on_sphere, vertical;
  on_sphere.reserve(data.samples.size());
  vertical.reserve(data.samples.size());
  for (std::size_t i = 0; i < data.samples.size(); ++i) {
    if (!data.samples[i].has_mag) continue;
    on_sphere.push_back(d_tilde_inv * (data.samples[i].mag_unit - fit.offset_uT / options.field_norm_uT));
    vertical.push_back(vertical_all[i]);
  }
  const std::vector<MisalignmentEstimate> minima = misalignmentMinima(on_sphere, vertical);
  MisalignmentEstimate mis = minima.front();
  if (options.expected_dip_sign != DipSign::kUnknown) {
    // The best minimum of the expected sign (the mirror of the other sign explains the same
    // inner products, dip_sign.hpp); the best of all when none has it.
    for (const MisalignmentEstimate& m : minima) {
      if (dipAgrees(m.field_down, options.expected_dip_sign)) {
        out.misalignment_sign_chosen = &m != &minima.front();
        mis = m;
        break;
      }
    }
  }
  out.misalignment_minima = static_cast<int>(minima.size());
  out.misalignment = mis.rotation;
  out.misalignment_rms = mis.rms_residual;
  out.dip_rad = mis.dip_rad;
  out.D = fit.D * mis.rotation;  // eq. 28a
  return out;
}

MlParameterValues initialParameterValues(const MlInitialEstimate& initial, const MlInitialOptions& options) {
  MlParameterValues v;
  v.D = initial.D;
  v.offset = initial.offset_uT / initial.field_norm_uT;
  v.dip_rad = initial.dip_rad;
  v.gyro_bias_rad_s = initial.gyro_bias_rad_s;
  v.gyro_cov = withFloor(initial.gyro_cov, options.min_gyro_sigma_rad_s);
  v.accel_cov = withFloor(initial.accel_cov, options.min_accel_sigma_m_s2);
  const double f2 = initial.field_norm_uT * initial.field_norm_uT;
  v.mag_cov = withFloor(initial.mag_cov_uT2, options.min_mag_sigma_uT) / f2;
  return v;
}

}  // namespace headingd::calib
