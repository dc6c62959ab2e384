#pragma once
// The cost of Kok & Schön (2016) eq. 6: ½ Σ_t ‖y_t - ŷ_t|t-1(θ)‖²_{S_t⁻¹} + log det S_t,
// with ŷ and S from the EKF of ml_ekf.hpp. Templated on the scalar: double for the value,
// ceres::Jet for its exact gradient.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "headingd/calib/ml/ml_data.hpp"
#include "headingd/calib/ml/ml_ekf.hpp"
#include "headingd/calib/ml/ml_parameters.hpp"

namespace headingd::calib {

// The EKF's first attitude's uncertainty: a TRIAD from the mean of a few samples.
inline constexpr double kMlInitialAttitudeSigma_rad = 0.05;

// Normalised residuals L_t⁻¹(y_t - ŷ_t|t-1) of one sample (K&S §7.2, Figs. 5-6); the
// magnetometer part is NaN where the sample has none.
struct MlResidual {
  core::Vec3 accel = core::Vec3::Zero();
  core::Vec3 mag = core::Vec3::Zero();
  bool has_mag = false;
};

// Mean accelerometer and raw magnetometer of the first `initial_average_samples` samples.
inline void initialMeans(const MlData& data, core::Vec3& accel, core::Vec3& mag, bool& have_mag) {
  const std::size_t n = std::min(std::max<std::size_t>(data.initial_average_samples, 1), data.samples.size());
  accel.setZero();
  mag.setZero();
  std::size_t mags = 0;
  for (std::size_t i = 0; i < n; ++i) {
    accel += data.samples[i].accel_m_s2;
    if (data.samples[i].has_mag) {
      mag += data.samples[i].mag_unit;
      ++mags;
    }
  }
  accel /= static_cast<double>(std::max<std::size_t>(n, 1));
  have_mag = mags > 0;
  if (have_mag) mag /= static_cast<double>(mags);
}

// The predictor's start: false when `model` is outside θ's domain, else `ekf` initialised
// from the first samples.
template <typename T>
bool mlStartPredictor(const MlModel<T>& model, const MlData& data, MlEkf<T>& ekf) {
  if (data.samples.empty()) return false;
  // Two mirror modes fit the magnetometer almost as well and give headings wrong by up to
  // 180° (seen in 3 of 30 K&S §8 runs): a dip beyond ±90° (the field's horizontal part
  // pointing south, m_n(π - δ) = Rz(π) m_n(δ)) and -D with the field reversed
  // (m_n(-δ) = -Rz(π) m_n(δ)). North is the field's horizontal direction (+x) and the
  // initial estimate has det D > 0, so both are outside θ's domain, and so is a dip of the
  // sign the place rules out (dip_sign.hpp): returning false makes the line search step back.
  if (!(model.field_n.x() > T(0.0)) || !(model.D.determinant() > T(0.0)) ||
      !dipAgrees(model.field_n.z(), data.expected_dip_sign)) {
    return false;
  }
  core::Vec3 accel0, mag0;
  bool have_mag0 = false;
  initialMeans(data, accel0, mag0, have_mag0);
  if (have_mag0) {
    ekf.initialise(accel0.cast<T>(), mag0.cast<T>(), kMlInitialAttitudeSigma_rad);
  } else {
    ekf.initialiseFromGravity(accel0.cast<T>(), kMlInitialAttitudeSigma_rad);
  }
  return true;
}

// One step t of the predictor: the time update with the sample's gyro, then its accelerometer
// and (when it has one) magnetometer factors of eq. 6, added to `cost`. False if an
// innovation covariance is not positive definite. `residual`, when given, receives the
// normalised innovations.
template <typename T>
bool mlPredictorStep(MlEkf<T>& ekf, const MlSample& s, T& cost, MlResidual* residual) {
  ekf.predict(s.gyro_rad_s, s.dt_s, s.gyro_noise_dt2_s2);
  const InnovationTerm<T> a = s.accel_count > 1
                                  ? ekf.updateAccelMean(s.accel_m_s2, s.accel_mean_rotation, s.accel_count)
                                  : ekf.updateAccel(s.accel_m_s2);
  if (!a.ok) return false;
  cost += a.cost;
  if (residual) {
    for (int k = 0; k < 3; ++k) residual->accel(k) = scalarPart(a.normalised(k));
  }
  if (s.has_mag) {
    const InnovationTerm<T> m =
        s.mag_count > 1 ? ekf.updateMagMean(s.mag_unit, s.mag_mean_rotation, s.mag_count) : ekf.updateMag(s.mag_unit);
    if (!m.ok) return false;
    cost += m.cost;
    if (residual) {
      for (int k = 0; k < 3; ++k) residual->mag(k) = scalarPart(m.normalised(k));
      residual->has_mag = true;
    }
  } else if (residual) {
    residual->mag.setConstant(std::nan(""));
  }
  return true;
}

// Runs the EKF over `data` with `model` and returns the cost of eq. 6 (without the constant
// 3 log 2π per factor). False if an innovation covariance stops being positive definite or
// the cost is not finite; `residuals`, when given, receives one entry per sample.
template <typename T>
bool mlNegativeLogLikelihood(const MlModel<T>& model, const MlData& data, T& cost,
                             std::vector<MlResidual>* residuals = nullptr) {
  using std::isfinite;
  cost = T(0.0);
  MlEkf<T> ekf(model, data.gravity_m_s2);
  if (!mlStartPredictor(model, data, ekf)) return false;
  if (residuals) residuals->assign(data.samples.size(), MlResidual{});
  for (std::size_t i = 0; i < data.samples.size(); ++i) {
    if (!mlPredictorStep(ekf, data.samples[i], cost, residuals ? &(*residuals)[i] : nullptr)) return false;
  }
  return isfinite(cost);
}

// The functor Ceres's first-order functions call: θ (34 numbers) → cost.
class MlCostFunctor {
 public:
  explicit MlCostFunctor(const MlData* data) : data_(data) {}
  template <typename T>
  bool operator()(const T* theta, T* cost) const {
    return mlNegativeLogLikelihood<T>(modelFromParameters<T>(theta), *data_, *cost);
  }

 private:
  const MlData* data_;
};

}  // namespace headingd::calib
