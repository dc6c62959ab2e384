// The quaternion EKF of Henriksson ch. 3 (Algorithm 2), one step at a time.
#include "headingd/core/attitude_ekf.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kRadPerDeg;
using test::Random;

constexpr double kG = 9.81;

// The specific force an accelerometer at rest reads in body axes for attitude q_nb.
Vec3 gravityReading(const Quat& q_nb) { return q_nb.inverse() * Vec3(0.0, 0.0, -kG); }

// Body "down" as the estimate sees it.
Vec3 downInBody(const Quat& q_nb) { return q_nb.inverse() * Vec3::UnitZ(); }

// A covariance that lies in the tangent space at q, as the filter keeps it.
Mat4 tangentCovariance(const Vec4& q, double sigma) {
  const Mat4 project = Mat4::Identity() - q * q.transpose();
  return sigma * sigma * project;
}

TEST(AttitudeEkf, StartsAtIdentityWithAlgorithm2Covariance) {
  const AttitudeEkf ekf;
  EXPECT_EQ(ekf.state(), Vec4(1, 0, 0, 0));
  EXPECT_EQ(ekf.covariance(), 1000.0 * Mat4::Identity());
}

TEST(AttitudeEkf, PredictWithZeroNoiseIntegratesConstantRateExactly) {
  AttitudeEkf ekf;
  const Quat q0 = test::fromYawPitchRoll(0.3, -0.2, 0.5);
  ekf.setAttitude(q0);
  const Vec3 w(0.4, -1.1, 0.8);
  const double dt = 0.01;
  const int steps = 500;
  for (int i = 0; i < steps; ++i) ekf.predict(w, dt, 0.0);
  const Quat expected = q0 * Quat(Eigen::AngleAxisd(w.norm() * dt * steps, w.normalized()));
  EXPECT_LT(test::angleBetween(ekf.attitude(), expected), 1e-11);
  EXPECT_NEAR(ekf.state().norm(), 1.0, 1e-15);
}

TEST(AttitudeEkf, PredictAddsQAndKeepsPSymmetric) {
  AttitudeEkf ekf;
  ekf.setAttitude(test::fromYawPitchRoll(1.0, 0.3, -0.4));
  ekf.setCovariance(tangentCovariance(ekf.state(), 0.01));
  const Vec3 w(0.5, 0.2, -0.9);
  const double dt = 0.01, sigma = 0.004;

  const Vec4 q_before = ekf.state();
  const Mat4 P_before = ekf.covariance();
  ekf.predict(w, dt, sigma);

  // Eq. 3.3: P = F P Fᵀ + Q with Q = (dt/2)² Ξ Σ Ξᵀ, Σ = σ² I. F is orthogonal, so the
  // trace grows by trace(Q) = (dt σ/2)² · 3 |q|². (Whether the sliver of Q along the new q,
  // about |ω| dt/2 of it, is projected out is the filter's choice: allowed for.)
  const Mat4 F = gyroTransition(w, dt);
  const Mat43 xi = rightProductMatrix(q_before);
  const Mat4 Q = std::pow(0.5 * dt * sigma, 2) * xi * xi.transpose();
  const Mat4 expected = F * P_before * F.transpose() + Q;
  EXPECT_LT((ekf.covariance() - expected).norm(), 0.05 * Q.norm());
  EXPECT_LT((ekf.state() - F * q_before).norm(), 1e-15);
  const double trace_q = 3.0 * std::pow(0.5 * dt * sigma, 2);
  EXPECT_NEAR(ekf.covariance().trace() - P_before.trace(), trace_q, 0.05 * trace_q);
  EXPECT_GT(ekf.covariance().trace(), P_before.trace());
  EXPECT_LT((ekf.covariance() - ekf.covariance().transpose()).norm(), 1e-18);

  // Over many steps the trace keeps growing and P stays symmetric.
  double last_trace = ekf.covariance().trace();
  for (int i = 0; i < 1000; ++i) {
    ekf.predict(w, dt, sigma);
    EXPECT_GT(ekf.covariance().trace(), last_trace);
    last_trace = ekf.covariance().trace();
  }
  EXPECT_LT((ekf.covariance() - ekf.covariance().transpose()).norm(), 1e-18);
}

TEST(AttitudeEkf, GravityUpdateMovesTiltTowardsTruthAndShrinksP) {
  Random rng(21);
  for (int trial = 0; trial < 50; ++trial) {
    const Quat truth = test::fromYawPitchRoll(rng.uniform(-3.0, 3.0), rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2));
    // A wrong tilt: truth rotated by up to 25° about a random horizontal axis.
    const Vec3 axis(rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0);
    const Quat wrong = Quat(Eigen::AngleAxisd(rng.uniform(5.0, 25.0) * kRadPerDeg, axis.normalized())) * truth;

    AttitudeEkf ekf;
    ekf.setAttitude(wrong);
    ekf.setCovariance(tangentCovariance(ekf.state(), 0.05));
    const double tilt_error_before = test::angleBetween(downInBody(ekf.attitude()), downInBody(truth));
    const double trace_before = ekf.covariance().trace();

    ekf.updateGravity(gravityReading(truth), 0.5, kG);

    const double tilt_error_after = test::angleBetween(downInBody(ekf.attitude()), downInBody(truth));
    EXPECT_LT(tilt_error_after, tilt_error_before) << "trial " << trial;
    EXPECT_LT(ekf.covariance().trace(), trace_before) << "trial " << trial;
    EXPECT_LT((ekf.covariance() - ekf.covariance().transpose()).norm(), 1e-15);
  }
}

TEST(AttitudeEkf, GravityUpdateNeverIncreasesTheCovariance) {
  // A measurement update only adds information: P after ≤ P before (Joseph form, eq. 3.7b),
  // whatever the measurement. Here: outliers such as a tap or a shock (a ±16 g accelerometer
  // can read 160 m/s²), from the start-up covariance the Estimator uses.
  Random rng(26);
  for (const double magnitude : {10.0, 30.0, 160.0}) {
    double worst_growth = 0.0;  // largest trace(P after) / trace(P before)
    for (int trial = 0; trial < 20; ++trial) {
      AttitudeEkf ekf;
      ekf.setAttitude(rng.unitQuat());
      ekf.setCovariance(tangentCovariance(ekf.state(), 0.05));
      const double trace_before = ekf.covariance().trace();
      ekf.updateGravity(rng.unitVector() * magnitude, 0.5, kG);
      worst_growth = std::max(worst_growth, ekf.covariance().trace() / trace_before);
    }
    EXPECT_LE(worst_growth, 1.0 + 1e-12) << "|a| = " << magnitude << " m/s²";
  }
}

TEST(AttitudeEkf, AMeasurementLessCertainAlongOneDirectionIsTheKalmanUpdateWithThatR) {
  // R = σ² I + v u uᵀ (a clipped accelerometer's low-pass, less certain along its clipped
  // axes): the whitened update must be the textbook one, q + P Hᵀ (H P Hᵀ + R)⁻¹ (a - h(q)),
  // with the filter's own P. From the tilt form (after a first update) and from the start-up P.
  Random rng(31);
  for (int trial = 0; trial < 40; ++trial) {
    AttitudeEkf ekf;
    ekf.setAttitude(rng.unitQuat());
    ekf.setCovariance(tangentCovariance(ekf.state(), rng.uniform(0.01, 0.1)));
    if (trial % 2 == 0) ekf.updateGravity(gravityReading(ekf.attitude()) + rng.vector(-1.0, 1.0), 0.5, kG);
    const Vec3 accel = gravityReading(ekf.attitude()) + rng.vector(-3.0, 3.0);
    const Vec3 u = rng.unitVector();
    const double sigma = rng.uniform(0.3, 3.0);
    const double extra = std::pow(rng.uniform(0.1, 30.0), 2);

    const Vec4 q = ekf.state();
    const Mat4 P = ekf.covariance();
    const Vec3 f_n(0.0, 0.0, -kG);
    const Mat34 H = rotateEarthToBodyJacobian(q, f_n);
    const Mat3 R = sigma * sigma * Mat3::Identity() + extra * u * u.transpose();
    const Mat3 S = H * P * H.transpose() + R;
    const Vec4 expected = (q + P * H.transpose() * S.inverse() * (accel - rotateEarthToBody(q, f_n))).normalized();

    ekf.updateGravity(accel, sigma, kG, u, extra);
    EXPECT_LT((ekf.state() - expected).norm(), 1e-9) << "trial " << trial;
  }
}

TEST(AttitudeEkf, AMeasurementShortAlongItsUncertainDirectionBarelyTilts) {
  // A low-pass 3 m/s² short along a sensor axis 30° off vertical (the accelerometer clipped
  // there) pulls the tilt by degrees; told that direction is uncertain by 16 m/s², the update
  // keeps to what the other two directions say, which is the truth.
  const Quat truth = test::fromYawPitchRoll(0.7, 30.0 * kRadPerDeg, 0.0);
  const Vec3 clipped_axis = Vec3::UnitX();
  const Vec3 short_reading = gravityReading(truth) - 3.0 * clipped_axis;
  const auto tilt_after = [&](double extra_variance) {
    AttitudeEkf ekf;
    ekf.setAttitude(truth);
    ekf.setCovariance(tangentCovariance(ekf.state(), 0.05));
    for (int i = 0; i < 300; ++i) {
      ekf.predict(Vec3::Zero(), 0.01, 0.08);
      ekf.updateGravity(short_reading, 0.5, kG, clipped_axis, extra_variance);
    }
    return test::angleBetween(downInBody(ekf.attitude()), downInBody(truth));
  };
  const double plain = tilt_after(0.0);
  const double told = tilt_after(16.0 * 16.0);
  EXPECT_GT(plain, 5.0 * kRadPerDeg);
  EXPECT_LT(told, 0.1 * plain);
}

TEST(AttitudeEkf, RepeatedUpdatesAtRestConvergeToRollAndPitch) {
  const Quat truth = test::fromYawPitchRoll(2.0, 20.0 * kRadPerDeg, -35.0 * kRadPerDeg);
  AttitudeEkf ekf;
  ekf.setAttitude(test::fromYawPitchRoll(2.0, -10.0 * kRadPerDeg, 10.0 * kRadPerDeg));
  ekf.setCovariance(tangentCovariance(ekf.state(), 0.1));
  for (int i = 0; i < 1000; ++i) {
    ekf.predict(Vec3::Zero(), 0.01, 0.004);
    ekf.updateGravity(gravityReading(truth), 0.5, kG);
  }
  const EulerAngles e = eulerZyx(ekf.attitude());
  EXPECT_NEAR(e.roll_rad, -35.0 * kRadPerDeg, 0.1 * kRadPerDeg);
  EXPECT_NEAR(e.pitch_rad, 20.0 * kRadPerDeg, 0.1 * kRadPerDeg);
}

TEST(AttitudeEkf, ConsistentGravityLeavesHeadingAlone) {
  // The accelerometer says nothing about heading: with noisy readings of the right gravity,
  // the heading of an attitude already consistent with gravity barely moves.
  Random rng(22);
  for (int trial = 0; trial < 10; ++trial) {
    const double yaw = rng.uniform(-3.0, 3.0);
    const Quat truth = test::fromYawPitchRoll(yaw, rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2));
    AttitudeEkf ekf;
    ekf.setAttitude(truth);
    ekf.setCovariance(tangentCovariance(ekf.state(), 0.05));
    for (int i = 0; i < 500; ++i) {
      ekf.predict(Vec3::Zero(), 0.01, 0.004);
      ekf.updateGravity(gravityReading(truth) + rng.gaussian(0.05), 0.5, kG);
    }
    EXPECT_LT(test::angleDifference(eulerZyx(ekf.attitude()).yaw_rad, yaw), 0.2 * kRadPerDeg) << "trial " << trial;
    EXPECT_LT(test::angleBetween(ekf.attitude(), truth), 0.5 * kRadPerDeg) << "trial " << trial;
  }
}

TEST(AttitudeEkf, ExactGravityAtTheTrueAttitudeChangesNothing) {
  const Quat truth = test::fromYawPitchRoll(-1.0, 0.4, 0.9);
  AttitudeEkf ekf;
  ekf.setAttitude(truth);
  ekf.setCovariance(tangentCovariance(ekf.state(), 0.05));
  ekf.updateGravity(gravityReading(truth), 0.5, kG);
  EXPECT_LT(test::angleBetween(ekf.attitude(), truth), 1e-12);
}

TEST(AttitudeEkf, StateStaysNormalisedWithNonNegativeW) {
  AttitudeEkf ekf;
  ekf.setCovariance(tangentCovariance(ekf.state(), 0.05));
  Random rng(23);
  // Fast rotation for several turns: w passes through zero many times.
  const Vec3 w(3.0, -2.0, 4.0);
  for (int i = 0; i < 2000; ++i) {
    ekf.predict(w, 0.01, 0.004);
    EXPECT_NEAR(ekf.state().norm(), 1.0, 1e-14);
    EXPECT_GE(ekf.state()(0), 0.0);
    ekf.updateGravity(rng.vector(-15.0, 15.0), 2.0, kG);
    EXPECT_NEAR(ekf.state().norm(), 1.0, 1e-14);
    EXPECT_GE(ekf.state()(0), 0.0);
    ASSERT_TRUE(ekf.covariance().allFinite());
  }
}

TEST(AttitudeEkf, AfterAGravityUpdatePHasNoNormDirection) {
  // The norm of q is not a degree of freedom (eq. 3.8 discards it): after an update P lies
  // in the tangent space at q, even from Algorithm 2's P = 1000 I.
  AttitudeEkf ekf;
  ekf.setAttitude(test::fromYawPitchRoll(0.5, 0.1, 0.2));
  ekf.predict(Vec3(0.1, 0.2, 0.3), 0.01, 0.004);
  ekf.updateGravity(Vec3(0.5, -1.0, -9.7), 0.5, kG);
  EXPECT_LT((ekf.covariance() * ekf.state()).norm(), 1e-12 * ekf.covariance().norm());
}

// Columns e_x ⊗ q, e_y ⊗ q, e_z ⊗ q (Eigen products): how q moves when the attitude turns
// about the NED axes.
Eigen::Matrix<double, 4, 3> nedAxisDirections(const Vec4& q) {
  Eigen::Matrix<double, 4, 3> g;
  for (int i = 0; i < 3; ++i) {
    const Vec3 e = Vec3::Unit(i);
    g.col(i) = toWxyz(Quat(0.0, e.x(), e.y(), e.z()) * fromWxyz(q));
  }
  return g;
}

TEST(AttitudeEkf, SetAttitudeNormalisesAndFlipsToPositiveW) {
  AttitudeEkf ekf;
  const Quat q = test::fromYawPitchRoll(0.7, -0.3, 1.1);
  ekf.setAttitude(Quat(-2.0 * q.w(), -2.0 * q.x(), -2.0 * q.y(), -2.0 * q.z()));  // same rotation, scaled, w < 0
  EXPECT_NEAR(ekf.state().norm(), 1.0, 1e-15);
  EXPECT_GE(ekf.state()(0), 0.0);
  EXPECT_LT(test::angleBetween(ekf.attitude(), q), 1e-15);
  EXPECT_LT((ekf.state() - toWxyz(q.w() >= 0 ? q : Quat(-q.w(), -q.x(), -q.y(), -q.z()))).norm(), 1e-15);
}

TEST(AttitudeEkf, SetAttitudeKeepsTheCovarianceAboutTheNedAxes) {
  // The replacement is a better estimate of the same state: how uncertain roll, pitch and
  // heading are (P expressed about the NED axes) does not change, P just moves to the new q.
  Random rng(24);
  for (int trial = 0; trial < 20; ++trial) {
    AttitudeEkf ekf;
    ekf.setAttitude(rng.unitQuat());
    const Eigen::Matrix<double, 4, 3> g_before = nedAxisDirections(ekf.state());
    Mat3 root;
    root << rng.vector(-0.1, 0.1), rng.vector(-0.1, 0.1), rng.vector(-0.1, 0.1);
    const Mat3 about_ned = root * root.transpose() + 1e-4 * Mat3::Identity();  // symmetric positive definite
    ekf.setCovariance(g_before * about_ned * g_before.transpose());

    ekf.setAttitude(rng.unitQuat());
    const Eigen::Matrix<double, 4, 3> g_after = nedAxisDirections(ekf.state());
    EXPECT_LT((g_after.transpose() * ekf.covariance() * g_after - about_ned).norm(), 1e-15) << trial;
    EXPECT_LT((ekf.covariance() * ekf.state()).norm(), 1e-15) << trial;  // in the tangent space
  }
}

TEST(AttitudeEkf, GravityUpdateLeavesNoHeadingTiltCovariance) {
  // Heading is the magnetometer's (eq. 4.2): after a gravity update, P about the NED axes has
  // no terms between heading (about down) and tilt (about north and east).
  Random rng(25);
  AttitudeEkf ekf;
  const Quat truth = test::fromYawPitchRoll(1.2, 0.3, -0.2);
  ekf.setAttitude(test::fromYawPitchRoll(0.8, 0.1, 0.1));
  ekf.setCovariance(tangentCovariance(ekf.state(), 0.05));
  for (int i = 0; i < 50; ++i) {
    ekf.predict(rng.vector(-1.0, 1.0), 0.01, 0.004);
    ekf.updateGravity(gravityReading(truth) + rng.gaussian(0.1), 0.5, kG);
    const Eigen::Matrix<double, 4, 3> g = nedAxisDirections(ekf.state());
    const Mat3 about_ned = g.transpose() * ekf.covariance() * g;
    EXPECT_LT((about_ned.block<2, 1>(0, 2).norm()), 1e-15 * about_ned.norm()) << i;
    EXPECT_LT((about_ned.block<1, 2>(2, 0).norm()), 1e-15 * about_ned.norm()) << i;
  }
}

TEST(AttitudeEkf, TheTiltCovarianceIsPAboutNorthAndEastInRadians) {
  // q + G t turns the attitude by 2 t about the NED axes, so the tilt's covariance in rad² is
  // 4 Gᵀ P G over north and east: before the first gravity update (P general) and after (the
  // tilt form), through predictions and updates.
  Random rng(26);
  AttitudeEkf ekf;
  ekf.setAttitude(test::fromYawPitchRoll(0.8, 0.1, 0.1));
  ekf.setCovariance(tangentCovariance(ekf.state(), 0.05));
  const auto expectAboutNorthAndEast = [&ekf](int step) {
    const Eigen::Matrix<double, 4, 3> g = nedAxisDirections(ekf.state());
    const Eigen::Matrix2d expected = 4.0 * (g.transpose() * ekf.covariance() * g).topLeftCorner<2, 2>();
    EXPECT_LT((ekf.tiltCovariance() - expected).norm(), 1e-12 * expected.norm()) << step;
  };
  expectAboutNorthAndEast(-1);
  EXPECT_NEAR(ekf.tiltCovariance()(0, 0), 4.0 * 0.05 * 0.05, 1e-15);
  for (int i = 0; i < 20; ++i) {
    ekf.predict(rng.vector(-1.0, 1.0), 0.01, 0.004);
    ekf.updateGravity(gravityReading(test::fromYawPitchRoll(0.7, 0.2, 0.0)) + rng.gaussian(0.1), 0.5, kG);
    expectAboutNorthAndEast(i);
  }
}

}  // namespace
}  // namespace headingd::core
