// Quaternion algebra of core/quaternion.hpp, each function against an independent Eigen
// construction (Hamilton products, AngleAxis) rather than against a copy of its formula.
#include "headingd/core/quaternion.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kPi;
using test::kRadPerDeg;
using test::Random;

// q ⊗ (0, v) as a 4-vector (w, x, y, z), with Eigen's Hamilton product.
Vec4 productWithPure(const Quat& q, const Vec3& v) { return toWxyz(q * Quat(0.0, v.x(), v.y(), v.z())); }

// Rotation by the rotation vector φ (angle |φ| about φ/|φ|), with Eigen.
Quat expRotationVector(const Vec3& phi) {
  const double angle = phi.norm();
  return angle > 0.0 ? Quat(Eigen::AngleAxisd(angle, phi / angle)) : Quat::Identity();
}

TEST(Quaternion, WxyzRoundTripKeepsEveryComponent) {
  const Vec4 v(0.1, -0.2, 0.3, -0.4);  // not unit length: the conversion must not normalise
  const Quat q = fromWxyz(v);
  EXPECT_EQ(q.w(), 0.1);
  EXPECT_EQ(q.x(), -0.2);
  EXPECT_EQ(q.y(), 0.3);
  EXPECT_EQ(q.z(), -0.4);
  EXPECT_EQ(toWxyz(q), v);

  Random rng(1);
  for (int i = 0; i < 100; ++i) {
    const Quat r = rng.unitQuat();
    EXPECT_EQ(fromWxyz(toWxyz(r)).coeffs(), r.coeffs());
  }
}

TEST(Quaternion, OmegaMatrixIsTheHamiltonProductWithTheRate) {
  Random rng(2);
  for (int i = 0; i < 200; ++i) {
    const Quat q = rng.unitQuat();
    const Vec3 w = rng.vector(-5.0, 5.0);
    EXPECT_LT((omegaMatrix(w) * toWxyz(q) - productWithPure(q, w)).norm(), 1e-14);
  }
}

TEST(Quaternion, OmegaMatrixTimesQIsTwiceTheDerivative) {
  // q(t) = q0 ⊗ exp(½ ω t) for a constant body rate; Henriksson eq. 2.38: dq/dt = ½ Ω(ω) q.
  Random rng(3);
  const double h = 1e-5;
  for (int i = 0; i < 100; ++i) {
    const Quat q0 = rng.unitQuat();
    const Vec3 w = rng.vector(-3.0, 3.0);
    const Vec4 ahead = toWxyz(q0 * expRotationVector(w * h));
    const Vec4 behind = toWxyz(q0 * expRotationVector(-w * h));
    const Vec4 derivative = (ahead - behind) / (2.0 * h);
    EXPECT_LT((omegaMatrix(w) * toWxyz(q0) - 2.0 * derivative).norm(), 1e-8) << "sample " << i;
  }
}

TEST(Quaternion, GyroTransitionRotatesByTheIntegratedRate) {
  Random rng(4);
  for (int i = 0; i < 200; ++i) {
    const Quat q = rng.unitQuat();
    const Vec3 w = rng.vector(-10.0, 10.0);  // up to fast hand-held motion
    const double dt = rng.uniform(1e-4, 0.1);
    const Vec4 expected = toWxyz(q * expRotationVector(w * dt));
    const Vec4 actual = gyroTransition(w, dt) * toWxyz(q);
    EXPECT_LT((actual - expected).norm(), 1e-13) << "sample " << i;
  }
}

TEST(Quaternion, GyroIncrementIsTheRotationOfTheIntegratedRate) {
  // Henriksson eq. 2.34: q(t + dt) = q(t) ⊗ exp(½ ω dt).
  Random rng(41);
  for (int i = 0; i < 200; ++i) {
    const Vec3 w = rng.vector(-10.0, 10.0);
    const double dt = rng.uniform(1e-4, 0.1);
    const Quat r = gyroIncrement(w, dt);
    EXPECT_LT((r.coeffs() - expRotationVector(w * dt).coeffs()).norm(), 1e-15) << "sample " << i;
    EXPECT_NEAR(r.norm(), 1.0, 1e-15);
  }
  EXPECT_EQ(gyroIncrement(Vec3::Zero(), 0.01).coeffs(), Quat::Identity().coeffs());
}

TEST(Quaternion, RightMultiplicationMatrixIsTheHamiltonProductOnTheRight) {
  // F q = q ⊗ r, and F of the increment is the transition matrix.
  Random rng(42);
  for (int i = 0; i < 200; ++i) {
    const Quat q = rng.unitQuat();
    const Quat r = rng.unitQuat();
    EXPECT_LT((rightMultiplicationMatrix(r) * toWxyz(q) - toWxyz(q * r)).norm(), 1e-15) << "sample " << i;
    const Vec3 w = rng.vector(-5.0, 5.0);
    EXPECT_LT((rightMultiplicationMatrix(gyroIncrement(w, 0.01)) - gyroTransition(w, 0.01)).norm(), 1e-15);
  }
}

TEST(Quaternion, GyroTransitionOfZeroRateIsIdentity) {
  EXPECT_EQ(gyroTransition(Vec3::Zero(), 0.01), Mat4::Identity());
  EXPECT_EQ(gyroTransition(Vec3(1.0, 2.0, 3.0), 0.0), Mat4::Identity());
  // Tiny rates take the series branch of sinc; the result must still be the rotation.
  const Vec3 tiny(1e-9, -2e-9, 3e-9);
  const Quat q(Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()));
  EXPECT_LT((gyroTransition(tiny, 0.01) * toWxyz(q) - toWxyz(q * expRotationVector(tiny * 0.01))).norm(), 1e-16);
}

TEST(Quaternion, GyroTransitionIsOrthogonal) {
  // exp of a skew-symmetric matrix: keeps the norm of q exactly.
  Random rng(5);
  for (int i = 0; i < 50; ++i) {
    const Mat4 F = gyroTransition(rng.vector(-8.0, 8.0), rng.uniform(0.001, 0.05));
    EXPECT_LT((F.transpose() * F - Mat4::Identity()).norm(), 1e-14);
  }
}

TEST(Quaternion, GyroTransitionFirstOrderIsHenrikssonEq32) {
  // F = I + (dt/2) Ω(ω) + O(dt²): the residual shrinks by 4 when dt halves.
  const Vec3 w(0.7, -1.3, 2.1);
  const auto residual = [&](double dt) {
    return (gyroTransition(w, dt) - (Mat4::Identity() + 0.5 * dt * omegaMatrix(w))).norm();
  };
  for (double dt : {1e-2, 1e-3, 1e-4}) {
    // F - (I + ½Ω dt) = (cos θ - 1) I + O(θ³) with θ = ½|ω|dt, and ‖I‖_F = 2: about θ².
    const double theta = 0.5 * w.norm() * dt;
    EXPECT_LE(residual(dt), 1.001 * theta * theta) << "dt " << dt;
    EXPECT_NEAR(residual(dt) / residual(dt / 2), 4.0, 0.01) << "dt " << dt;
  }
}

TEST(Quaternion, RightProductMatrixIsTheHamiltonProductWithAPureQuaternion) {
  Random rng(6);
  for (int i = 0; i < 200; ++i) {
    const Quat q = rng.unitQuat();
    const Vec3 v = rng.vector(-2.0, 2.0);
    EXPECT_LT((rightProductMatrix(toWxyz(q)) * v - productWithPure(q, v)).norm(), 1e-14);
  }
  // Its columns are tangent to the unit sphere at q: Ξ(q)ᵀ q = 0.
  const Quat q = rng.unitQuat();
  EXPECT_LT((rightProductMatrix(toWxyz(q)).transpose() * toWxyz(q)).norm(), 1e-15);
}

TEST(Quaternion, RotateEarthToBodyIsTheInverseRotation) {
  Random rng(7);
  for (int i = 0; i < 200; ++i) {
    const Quat q_nb = rng.unitQuat();
    const Vec3 v_n = rng.vector(-50.0, 50.0);
    const Vec3 expected = q_nb.inverse() * v_n;
    EXPECT_LT((rotateEarthToBody(toWxyz(q_nb), v_n) - expected).norm(), 1e-12) << "sample " << i;
    // And back: the body vector rotated by q_nb is the earth vector again.
    EXPECT_LT((q_nb * rotateEarthToBody(toWxyz(q_nb), v_n) - v_n).norm(), 1e-12);
  }
  // A concrete case: heading 90° (body x points east); north is then on the body's left.
  const Quat east = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
  EXPECT_LT((rotateEarthToBody(toWxyz(east), Vec3::UnitX()) - Vec3(0, -1, 0)).norm(), 1e-15);
}

TEST(Quaternion, EulerZyxRecoversYawPitchRollBuiltWithEigen) {
  Random rng(8);
  for (int i = 0; i < 2000; ++i) {
    const double yaw = rng.uniform(-kPi, kPi);
    const double pitch = rng.uniform(-89.0 * kRadPerDeg, 89.0 * kRadPerDeg);
    const double roll = rng.uniform(-kPi, kPi);
    const EulerAngles e = eulerZyx(test::fromYawPitchRoll(yaw, pitch, roll));
    EXPECT_NEAR(test::angleDifference(e.yaw_rad, yaw), 0.0, 1e-9) << yaw << " " << pitch << " " << roll;
    EXPECT_NEAR(e.pitch_rad, pitch, 1e-9) << yaw << " " << pitch << " " << roll;
    EXPECT_NEAR(test::angleDifference(e.roll_rad, roll), 0.0, 1e-9) << yaw << " " << pitch << " " << roll;
  }
}

TEST(Quaternion, EulerZyxSignConventions) {
  // Nose up is positive pitch, right wing down positive roll, turning east positive yaw.
  EXPECT_NEAR(eulerZyx(Quat(Eigen::AngleAxisd(0.2, Vec3::UnitY()))).pitch_rad, 0.2, 1e-15);
  EXPECT_NEAR(eulerZyx(Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()))).roll_rad, 0.3, 1e-15);
  EXPECT_NEAR(eulerZyx(headingRotation(0.4)).yaw_rad, 0.4, 1e-15);
  // -q is the same rotation.
  const Quat q = test::fromYawPitchRoll(1.0, 0.5, -0.7);
  const EulerAngles a = eulerZyx(q), b = eulerZyx(Quat(-q.w(), -q.x(), -q.y(), -q.z()));
  EXPECT_NEAR(a.yaw_rad, b.yaw_rad, 1e-14);
  EXPECT_NEAR(a.pitch_rad, b.pitch_rad, 1e-14);
  EXPECT_NEAR(a.roll_rad, b.roll_rad, 1e-14);
}

TEST(Quaternion, HeadingRotationTurnsNorthTowardsEast) {
  const Vec3 north_turned = headingRotation(kPi / 2) * Vec3::UnitX();
  EXPECT_LT((north_turned - Vec3::UnitY()).norm(), 1e-15);
  EXPECT_LT((headingRotation(0.8) * Vec3::UnitZ() - Vec3::UnitZ()).norm(), 1e-15);  // down stays down
}

TEST(Quaternion, WrapAngleMapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrapAngle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(wrapAngle(1.0), 1.0);
  EXPECT_DOUBLE_EQ(wrapAngle(-1.0), -1.0);
  EXPECT_DOUBLE_EQ(wrapAngle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrapAngle(-kPi), kPi);  // -π is outside (-π, π]
  EXPECT_NEAR(wrapAngle(2.0 * kPi + 0.1), 0.1, 1e-15);
  EXPECT_NEAR(wrapAngle(-2.0 * kPi - 0.1), -0.1, 1e-15);
  EXPECT_NEAR(wrapAngle(3.0 * kPi / 2.0), -kPi / 2.0, 1e-15);
  EXPECT_NEAR(wrapAngle(-3.0 * kPi / 2.0), kPi / 2.0, 1e-15);
  EXPECT_NEAR(wrapAngle(101.0 * kPi + 0.25), -kPi + 0.25, 1e-12);
  Random rng(9);
  for (int i = 0; i < 1000; ++i) {
    const double a = rng.uniform(-1000.0, 1000.0);
    const double w = wrapAngle(a);
    EXPECT_GT(w, -kPi);
    EXPECT_LE(w, kPi);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-12);
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-12);
  }
}

TEST(Quaternion, NedToEnuSwapsNorthEastAndFlipsDown) {
  const Quat q_enu = nedToEnu(Quat::Identity());
  EXPECT_LT((q_enu * Vec3(1, 0, 0) - Vec3(0, 1, 0)).norm(), 1e-15);   // north → ENU y
  EXPECT_LT((q_enu * Vec3(0, 1, 0) - Vec3(1, 0, 0)).norm(), 1e-15);   // east → ENU x
  EXPECT_LT((q_enu * Vec3(0, 0, 1) - Vec3(0, 0, -1)).norm(), 1e-15);  // down → -up
}

TEST(Quaternion, NedToEnuComposesWithTheAttitude) {
  // For any q_nb, nedToEnu(q_nb) maps a body vector to the ENU coordinates of q_nb * v.
  Random rng(10);
  for (int i = 0; i < 100; ++i) {
    const Quat q_nb = rng.unitQuat();
    const Vec3 v_b = rng.vector(-1.0, 1.0);
    const Vec3 n = q_nb * v_b;
    EXPECT_LT((nedToEnu(q_nb) * v_b - Vec3(n.y(), n.x(), -n.z())).norm(), 1e-14);
  }
}

TEST(Quaternion, TiltedToSetsTheTiltFromADownDirectionAndKeepsTheHeading) {
  Random rng(91);
  for (int trial = 0; trial < 50; ++trial) {
    const Quat q = test::fromYawPitchRoll(rng.uniform(-3.0, 3.0), rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6));
    const Quat target = test::fromYawPitchRoll(yawZyx(q), rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6));
    const Vec3 down_b = target.conjugate() * Vec3::UnitZ();
    const Quat tilted = tiltedTo(q, 7.0 * down_b);  // any length
    EXPECT_NEAR(tilted.norm(), 1.0, 1e-12);
    EXPECT_LT(test::angleBetween(Vec3(tilted * down_b), Vec3::UnitZ()), 1e-9);
    // The heading moves only in second order of the tilt's change (up to 0.85 rad here).
    EXPECT_LT(test::angleDifference(yawZyx(tilted), yawZyx(q)), 0.2) << trial;
  }
  // A small change of tilt leaves the heading within a small fraction of it.
  const Quat q = test::fromYawPitchRoll(1.0, 0.1, 0.2);
  const Quat target = test::fromYawPitchRoll(1.0, 0.12, 0.19);
  const Quat tilted = tiltedTo(q, target.conjugate() * Vec3::UnitZ());
  EXPECT_LT(test::angleDifference(yawZyx(tilted), 1.0), 0.002);
}

}  // namespace
}  // namespace headingd::core
