// The measurement models (measurement_model.hpp): each model's Jacobian against central
// differences of its residual over the error state, at random states and measurements, and
// each model's residual zero where the measurement is exactly what the state predicts.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "headingd/core/magnetic_heading_model.hpp"
#include "headingd/core/quasi_static_field.hpp"
#include "headingd/core/reference_vector_model.hpp"
#include "headingd/core/rotated_vector_model.hpp"
#include "headingd/core/zero_rate_model.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kRadPerDeg;

NavigationState randomState(test::Random& rng) {
  NavigationState x;
  x.q_nb = rng.unitQuat();
  x.gyro_bias_rad_s = rng.gaussian(0.02);
  x.accel_bias_m_s2 = rng.gaussian(0.2);
  return x;
}

// ∂h/∂δx = -∂(z - h)/∂δx by central differences of the residual.
template <int N>
Eigen::Matrix<double, N, error_state::kSize> numericalJacobian(
    const NavigationState& x, const std::function<Linearised<N>(const NavigationState&)>& linearise) {
  constexpr double kStep = 1e-6;
  Eigen::Matrix<double, N, error_state::kSize> jacobian;
  for (int i = 0; i < error_state::kSize; ++i) {
    ErrorVector dx = ErrorVector::Zero();
    dx(i) = kStep;
    const auto plus = linearise(perturbed(x, dx)).residual;
    const auto minus = linearise(perturbed(x, -dx)).residual;
    jacobian.col(i) = -(plus - minus) / (2.0 * kStep);
  }
  return jacobian;
}

template <int N>
void expectJacobianMatches(const NavigationState& x,
                           const std::function<Linearised<N>(const NavigationState&)>& linearise, double scale) {
  const auto analytic = linearise(x).jacobian;
  const auto numerical = numericalJacobian<N>(x, linearise);
  EXPECT_LT((analytic - numerical).cwiseAbs().maxCoeff(), 1e-6 * scale) << "analytic\n"
                                                                        << analytic << "\nnumerical\n"
                                                                        << numerical;
}

TEST(MeasurementModels, ReferenceVectorJacobianMatchesNumerical) {
  test::Random rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const NavigationState x = randomState(rng);
    const ReferenceVectorModel gravity{Vec3(0.0, 0.0, -9.81), 0.05, /*with_accel_bias=*/true};
    const Vec3 accel = rng.gaussian(10.0);
    expectJacobianMatches<3>(
        x, [&](const NavigationState& s) { return gravity.linearise(s, accel); }, 10.0);
    const ReferenceVectorModel field{Vec3(18.0, -2.0, 45.0), 0.5};
    const Vec3 mag = rng.gaussian(50.0);
    expectJacobianMatches<3>(
        x, [&](const NavigationState& s) { return field.linearise(s, mag); }, 50.0);
  }
}

TEST(MeasurementModels, ReferenceVectorResidualIsZeroAtTheTruth) {
  test::Random rng(2);
  const NavigationState x = randomState(rng);
  const Vec3 gravity_ned(0.0, 0.0, -9.81);
  const ReferenceVectorModel gravity{gravity_ned, 0.05, true};
  const Vec3 accel = x.q_nb.conjugate() * gravity_ned + x.accel_bias_m_s2;
  EXPECT_LT(gravity.linearise(x, accel).residual.norm(), 1e-12);
  EXPECT_DOUBLE_EQ(gravity.linearise(x, accel).noise_covariance(1, 1), 0.05 * 0.05);
  // Gravity says nothing of the heading: the Jacobian's column about down is zero.
  EXPECT_LT(gravity.linearise(x, accel).jacobian.col(error_state::kAttitude + 2).norm(), 1e-12);
}

TEST(MeasurementModels, RotatedVectorJacobianMatchesNumerical) {
  test::Random rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const NavigationState x = randomState(rng);
    const Vec3 gyro = rng.gaussian(trial < 10 ? 0.5 : 5.0);  // slow, and fast as in a swung hand
    const double interval_s = 0.01 * (1 + trial % 4);
    const Vec3 before = rng.gaussian(30.0), after = rng.gaussian(30.0);
    const RotatedVectorModel maru{0.5};
    expectJacobianMatches<3>(
        x, [&](const NavigationState& s) { return maru.linearise(s, before, after, gyro, interval_s); }, 30.0);
    const RotatedVectorModel agu{0.05, /*with_accel_bias=*/true};
    expectJacobianMatches<3>(
        x, [&](const NavigationState& s) { return agu.linearise(s, before, after, gyro, interval_s); }, 30.0);
  }
}

TEST(MeasurementModels, RotatedVectorResidualIsZeroForAVectorFixedInTheEarth) {
  // A field fixed in NED, the sensor turning at a constant true rate for one interval: the
  // second reading is the first turned by the bias-corrected gyro.
  test::Random rng(4);
  NavigationState x = randomState(rng);
  const Vec3 rate(0.4, -1.1, 2.0);
  const double dt = 0.02;
  const Quat q_after = x.q_nb * gyroIncrement(rate, dt);
  const Vec3 field_ned(20.0, 1.0, 44.0);
  const RotatedVectorModel maru{0.5};
  const Vec3 gyro = rate + x.gyro_bias_rad_s;
  const auto l = maru.linearise(x, x.q_nb.conjugate() * field_ned, q_after.conjugate() * field_ned, gyro, dt);
  EXPECT_LT(l.residual.norm(), 1e-9);
  EXPECT_DOUBLE_EQ(l.noise_covariance(0, 0), 2.0 * 0.5 * 0.5);  // both samples' noise
  // The accelerometer's: the same with its bias added to both readings.
  const RotatedVectorModel agu{0.05, true};
  const Vec3 force_ned(0.3, -0.2, -9.81);
  const auto a = agu.linearise(x, x.q_nb.conjugate() * force_ned + x.accel_bias_m_s2,
                               q_after.conjugate() * force_ned + x.accel_bias_m_s2, gyro, dt);
  EXPECT_LT(a.residual.norm(), 1e-9);
  // The pair says nothing of the attitude itself.
  EXPECT_EQ((l.jacobian.block<3, 3>(0, error_state::kAttitude).norm()), 0.0);
}

// The interval form: the gyro's increments over a baseline of many samples composed with the
// bias b (GyroRotationIntegral), the field at its two ends. Its Jacobian against the residuals of
// the same readings composed again with b ± ε about each axis; its residual zero for a field
// fixed in the earth.
GyroRotationIntegral composed(const std::vector<Vec3>& gyro, const Vec3& bias, double dt) {
  GyroFrame frame;
  GyroRotationIntegral interval;
  interval.start(frame.frameFromSensor());
  for (const Vec3& w : gyro) {
    frame.advance(gyroIncrement(w - bias, dt));
    interval.add(frame.frameFromSensor(), dt);
  }
  return interval;
}

TEST(MeasurementModels, RotatedVectorOverABaselineJacobianMatchesRecomposition) {
  test::Random rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    const double dt = 0.01;
    // 2 s of a hand turning the sensor: a rate that wanders about several axes.
    std::vector<Vec3> gyro;
    Vec3 rate = rng.gaussian(0.5);
    for (int k = 0; k < 200; ++k) gyro.push_back(rate += rng.gaussian(0.05));
    NavigationState x = randomState(rng);
    const Vec3 before = rng.gaussian(30.0), after = rng.gaussian(30.0);
    const RotatedVectorModel maru{0.5};
    const auto at = [&](const Vec3& bias) {
      NavigationState s = x;
      s.gyro_bias_rad_s = bias;
      return maru.linearise(s, before, after, composed(gyro, bias, dt));
    };
    const auto l = at(x.gyro_bias_rad_s);
    constexpr double kStep = 1e-6;
    for (int i = 0; i < 3; ++i) {
      const Vec3 step = kStep * Vec3::Unit(i);
      const Vec3 numerical =
          -(at(x.gyro_bias_rad_s + step).residual - at(x.gyro_bias_rad_s - step).residual) / (2 * kStep);
      // The trapezoid's error is second order in the turn per sample (here up to 0.02 rad).
      EXPECT_LT((l.jacobian.col(error_state::kGyroBias + i) - numerical).norm(), 2e-3 * numerical.norm() + 1e-6)
          << "axis " << i << "\nanalytic " << l.jacobian.col(error_state::kGyroBias + i).transpose() << "\nnumerical "
          << numerical.transpose();
    }
    EXPECT_EQ((l.jacobian.block<3, 3>(0, error_state::kAttitude).norm()), 0.0);
  }
}

TEST(MeasurementModels, RotatedVectorOverABaselineResidualIsZeroForAFieldFixedInTheEarth) {
  test::Random rng(8);
  const NavigationState x = randomState(rng);
  const double dt = 0.01;
  std::vector<Vec3> gyro;
  Quat q_nb = x.q_nb;
  for (int k = 0; k < 300; ++k) {
    const Vec3 rate(0.3 * std::sin(0.02 * k), 1.0, -0.5 * std::cos(0.03 * k));
    gyro.push_back(rate + x.gyro_bias_rad_s);
    q_nb = q_nb * gyroIncrement(rate, dt);
  }
  const Vec3 field_ned(20.0, 1.0, 44.0);
  const RotatedVectorModel maru{0.5};
  const auto l = maru.linearise(x, x.q_nb.conjugate() * field_ned, q_nb.conjugate() * field_ned,
                                composed(gyro, x.gyro_bias_rad_s, dt));
  EXPECT_LT(l.residual.norm(), 1e-9);
  EXPECT_DOUBLE_EQ(l.noise_covariance(2, 2), 2.0 * 0.5 * 0.5);
}

TEST(MeasurementModels, ZeroRateObservesTheGyroBiasAlone) {
  test::Random rng(5);
  const NavigationState x = randomState(rng);
  const ZeroRateModel rest{0.003};
  const Vec3 gyro = x.gyro_bias_rad_s + Vec3(0.001, -0.002, 0.0005);
  expectJacobianMatches<3>(
      x, [&](const NavigationState& s) { return rest.linearise(s, gyro); }, 1.0);
  const auto l = rest.linearise(x, gyro);
  EXPECT_LT((l.residual - Vec3(0.001, -0.002, 0.0005)).norm(), 1e-15);
  EXPECT_EQ((l.jacobian.block<3, 3>(0, error_state::kAttitude).norm()), 0.0);
}

TEST(MeasurementModels, MagneticHeadingJacobianMatchesNumerical) {
  test::Random rng(6);
  for (int trial = 0; trial < 20; ++trial) {
    const NavigationState x = randomState(rng);
    const MagneticHeadingModel heading{2.0 * kRadPerDeg};
    // A field 40-75° of dip, seen by the sensor with the heading off by up to 60°.
    const double dip = (40.0 + 35.0 * rng.uniform(0.0, 1.0)) * kRadPerDeg;
    const Vec3 field_ned = 50.0 * Vec3(std::cos(dip), 0.0, std::sin(dip));
    const Quat seen = headingRotation(rng.uniform(-60.0, 60.0) * kRadPerDeg) * x.q_nb;
    const Vec3 field_sensor = seen.conjugate() * field_ned;
    expectJacobianMatches<1>(
        x, [&](const NavigationState& s) { return heading.linearise(s, field_sensor); }, 1.0);
  }
}

TEST(MeasurementModels, MagneticHeadingIsTheTurnToTheFieldsNorth) {
  test::Random rng(7);
  const NavigationState x = randomState(rng);
  const MagneticHeadingModel heading{2.0 * kRadPerDeg};
  const double dip = 65.0 * kRadPerDeg;
  const Vec3 field_ned = 50.0 * Vec3(std::cos(dip), 0.0, std::sin(dip));
  // The state's heading 10° short of the field's: the residual turns it by +10°.
  const Quat truth = headingRotation(10.0 * kRadPerDeg) * x.q_nb;
  const auto l = heading.linearise(x, truth.conjugate() * field_ned);
  EXPECT_NEAR(l.residual(0), 10.0 * kRadPerDeg, 1e-12);
  // 1 about down; -tan(dip) about the horizontal axis along the field (north, at the truth).
  NavigationState true_state = x;
  true_state.q_nb = truth;
  const auto at_truth = heading.linearise(true_state, truth.conjugate() * field_ned);
  EXPECT_NEAR(at_truth.jacobian(0, error_state::kAttitude + 2), 1.0, 1e-12);
  EXPECT_NEAR(at_truth.jacobian(0, error_state::kAttitude + 0), -std::tan(dip), 1e-9);
  EXPECT_NEAR(at_truth.jacobian(0, error_state::kAttitude + 1), 0.0, 1e-9);
  // A field pointing straight down has no heading to give.
  const auto vertical = heading.linearise(x, x.q_nb.conjugate() * Vec3(0.0, 0.0, 50.0));
  EXPECT_TRUE(std::isinf(vertical.noise_covariance(0, 0)));
  EXPECT_EQ(vertical.jacobian.norm(), 0.0);
}

TEST(MeasurementModels, SO3LeftJacobianMatchesTheExponential) {
  // exp(φ + δ) R(φ)ᵀ ≈ exp(J_l(φ) δ), small and large angles, and across the series' switch.
  test::Random rng(8);
  for (double angle : {0.0, 5e-5, 2e-4, 0.3, 2.5}) {
    const Vec3 phi = angle * rng.unitVector();
    const Mat3 J = so3LeftJacobian(phi);
    for (int i = 0; i < 3; ++i) {
      const Vec3 step = 1e-6 * Vec3::Unit(i);
      const Mat3 turned = rotationMatrix(phi + step) * rotationMatrix(phi).transpose();
      // The small rotation's vector from its antisymmetric part.
      const Vec3 seen(turned(2, 1) - turned(1, 2), turned(0, 2) - turned(2, 0), turned(1, 0) - turned(0, 1));
      EXPECT_LT((0.5 * seen - J * step).norm(), 1e-11) << "angle " << angle << " axis " << i;
    }
  }
}

}  // namespace
}  // namespace headingd::core
