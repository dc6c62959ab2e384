// The measurement Jacobians of the multiplicative EKF (K&S §5.2) against central differences
// of the measurement models over the orientation deviation η, q = exp(η/2) ⊗ q̃.
#include <gtest/gtest.h>

#include "headingd/calib/ml/ml_ekf.hpp"

namespace headingd::calib {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

MlModel<double> someModel() {
  MlModel<double> m;
  m.D << 1.1, 0.2, -0.1,  //
      -0.05, 0.8, 0.3,    //
      0.15, -0.2, 1.3;
  m.offset = Vec3(0.3, -0.5, 0.2);
  m.field_n = fieldFromDip<double>(1.2);
  return m;
}

template <typename F>
Mat3 numericJacobian(const Eigen::Quaterniond& q_ref, F&& model) {
  Mat3 J;
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    Vec3 eta = Vec3::Zero();
    eta(k) = h;
    const Vec3 plus = model(quaternionFromRotationVector<double>(eta) * q_ref);
    const Vec3 minus = model(quaternionFromRotationVector<double>(Vec3(-eta)) * q_ref);
    J.col(k) = (plus - minus) / (2.0 * h);
  }
  return J;
}

TEST(MlEkfJacobian, AccelerometerAndMagnetometerMatchNumericalDifferences) {
  const MlModel<double> model = someModel();
  for (const Vec3& axis_angle : {Vec3(0.1, -0.2, 0.3), Vec3(1.0, 2.0, -0.5), Vec3(-2.5, 0.3, 1.1)}) {
    const Eigen::Quaterniond q = quaternionFromRotationVector<double>(axis_angle);
    MlEkf<double> ekf(model, 9.81);
    ekf.setAttitude(q, 0.1);
    const Mat3 ja = numericJacobian(q, [&](const Eigen::Quaterniond& qq) {
      MlEkf<double> e(model, 9.81);
      e.setAttitude(qq, 0.1);
      return Vec3(e.predictedAccel());
    });
    const Mat3 jm = numericJacobian(q, [&](const Eigen::Quaterniond& qq) {
      MlEkf<double> e(model, 9.81);
      e.setAttitude(qq, 0.1);
      return Vec3(e.predictedMag());
    });
    EXPECT_LT((ekf.accelJacobian() - ja).cwiseAbs().maxCoeff(), 1e-6) << ekf.accelJacobian() << "\n" << ja;
    EXPECT_LT((ekf.magJacobian() - jm).cwiseAbs().maxCoeff(), 1e-7) << ekf.magJacobian() << "\n" << jm;
  }
}

TEST(MlEkfJacobian, PredictionTurnsBodyByTheGyroRate) {
  // A body turning at 1 rad/s about its own z for 0.5 s: the predicted gravity stays, the
  // predicted field turns by -0.5 rad about z in body axes.
  MlModel<double> model;
  model.field_n = Vec3(1.0, 0.0, 0.0);
  MlEkf<double> ekf(model, 9.81);
  ekf.setAttitude(Eigen::Quaterniond::Identity(), 0.1);
  for (int i = 0; i < 50; ++i) ekf.predict(Vec3(0.0, 0.0, 1.0), 0.01);
  EXPECT_NEAR(ekf.predictedMag().x(), std::cos(0.5), 1e-12);
  EXPECT_NEAR(ekf.predictedMag().y(), -std::sin(0.5), 1e-12);
  EXPECT_NEAR(ekf.predictedAccel().z(), -9.81, 1e-12);
  // Gyro noise grows the covariance: Σω T² per step, 50 steps.
  EXPECT_NEAR(ekf.covariance()(2, 2), 0.01 + 50 * 1.0 * 1e-4, 1e-12);
}

}  // namespace
}  // namespace headingd::calib
