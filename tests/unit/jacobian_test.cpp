// Every Jacobian against numerical differentiation (central differences), at many random
// points, as a function of the unnormalised 4-vector q = (w, x, y, z).
#include <gtest/gtest.h>

#include <functional>

#include "headingd/core/quaternion.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::Random;

// ∂f/∂q by central differences, column by column.
template <int Rows>
Eigen::Matrix<double, Rows, 4> numericJacobian(const std::function<Eigen::Matrix<double, Rows, 1>(const Vec4&)>& f,
                                               const Vec4& q) {
  Eigen::Matrix<double, Rows, 4> J;
  for (int j = 0; j < 4; ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(q(j)));
    Vec4 plus = q, minus = q;
    plus(j) += h;
    minus(j) -= h;
    J.col(j) = (f(plus) - f(minus)) / (2.0 * h);
  }
  return J;
}

// ‖A - B‖ relative to the size of B (absolute near zero).
double relativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / std::max(1.0, b.norm());
}

TEST(Jacobian, RotateEarthToBodyMatchesNumericalDerivativeAtUnitQ) {
  Random rng(11);
  for (int i = 0; i < 500; ++i) {
    const Vec4 q = toWxyz(rng.unitQuat());
    const Vec3 v = rng.vector(-20.0, 20.0);
    const std::function<Vec3(const Vec4&)> f = [&](const Vec4& x) { return rotateEarthToBody(x, v); };
    const Mat34 analytic = rotateEarthToBodyJacobian(q, v);
    const Mat34 numeric = numericJacobian<3>(f, q);
    EXPECT_LT(relativeError(analytic, numeric), 1e-6) << "sample " << i << "\nanalytic\n"
                                                      << analytic << "\nnumeric\n"
                                                      << numeric;
  }
}

TEST(Jacobian, RotateEarthToBodyMatchesNumericalDerivativeAtUnnormalisedQ) {
  // The EKF linearises around the state before normalisation (eq. 3.8 comes after 3.7), and
  // the formula is the derivative of the quadratic form: it must hold off the unit sphere.
  Random rng(12);
  for (int i = 0; i < 500; ++i) {
    const Vec4 q = toWxyz(rng.unitQuat()) * rng.uniform(0.5, 2.0);
    const Vec3 v = rng.vector(-20.0, 20.0);
    const std::function<Vec3(const Vec4&)> f = [&](const Vec4& x) { return rotateEarthToBody(x, v); };
    EXPECT_LT(relativeError(rotateEarthToBodyJacobian(q, v), numericJacobian<3>(f, q)), 1e-6) << "sample " << i;
  }
}

TEST(Jacobian, RotateEarthToBodyForGravityAtIdentity) {
  // A hand-checked case: at q = 1, f_n = (0, 0, -g); rotating about body x by a small angle
  // ε (q ≈ (1, ε/2, 0, 0)) turns gravity towards body y: h ≈ (0, -g ε, -g) → ∂h_y/∂q_x = -2g.
  const double g = 9.81;
  const Mat34 H = rotateEarthToBodyJacobian(Vec4(1, 0, 0, 0), Vec3(0, 0, -g));
  Mat34 expected;
  expected << 0, 0, 2 * g, 0,  //
      0, -2 * g, 0, 0,         //
      -2 * g, 0, 0, 0;
  EXPECT_LT((H - expected).norm(), 1e-12) << H;
}

TEST(Jacobian, RotateEarthToBodyIsQuadraticSoHqIsTwiceH) {
  // Euler's theorem for the homogeneous quadratic h: H(q) q = 2 h(q). This is why the EKF
  // uses h(q̂) rather than the H_k q̂ printed in Henriksson eq. 3.7a.
  Random rng(13);
  for (int i = 0; i < 100; ++i) {
    const Vec4 q = toWxyz(rng.unitQuat()) * rng.uniform(0.5, 2.0);
    const Vec3 v = rng.vector(-20.0, 20.0);
    EXPECT_LT((rotateEarthToBodyJacobian(q, v) * q - 2.0 * rotateEarthToBody(q, v)).norm(), 1e-11);
  }
}

TEST(Jacobian, GyroTransitionJacobianIsFItself) {
  // The prediction q ← F(ω, dt) q is linear in q, so its Jacobian (the F of eq. 3.3) is F.
  Random rng(14);
  for (int i = 0; i < 200; ++i) {
    const Vec3 w = rng.vector(-6.0, 6.0);
    const double dt = rng.uniform(1e-3, 0.05);
    const Mat4 F = gyroTransition(w, dt);
    const Vec4 q = toWxyz(rng.unitQuat()) * rng.uniform(0.5, 2.0);
    const std::function<Vec4(const Vec4&)> f = [&](const Vec4& x) { return F * x; };
    EXPECT_LT(relativeError(F, numericJacobian<4>(f, q)), 1e-8) << "sample " << i;
  }
}

TEST(Jacobian, GyroTransitionDerivativeInTimeIsHalfOmegaF) {
  // d/dt exp(½Ω dt) = ½Ω exp(½Ω dt): the continuous-time model of eq. 2.38.
  Random rng(15);
  for (int i = 0; i < 100; ++i) {
    const Vec3 w = rng.vector(-6.0, 6.0);
    const double dt = rng.uniform(1e-3, 0.05);
    const double h = 1e-7;
    const Mat4 numeric = (gyroTransition(w, dt + h) - gyroTransition(w, dt - h)) / (2.0 * h);
    const Mat4 analytic = 0.5 * omegaMatrix(w) * gyroTransition(w, dt);
    EXPECT_LT(relativeError(analytic, numeric), 1e-6) << "sample " << i;
  }
}

TEST(Jacobian, RightProductMatrixIsTheDerivativeOfQTimesExpInTheRate) {
  // Q_k of eq. 3.3 maps gyro noise through Ξ(q): ∂/∂ω [F(ω, dt) q] at ω = 0 is (dt/2) Ξ(q).
  Random rng(16);
  const double dt = 0.01;
  for (int i = 0; i < 100; ++i) {
    const Vec4 q = toWxyz(rng.unitQuat());
    Mat43 numeric;
    for (int j = 0; j < 3; ++j) {
      const double h = 1e-6;
      const Vec3 e = Vec3::Unit(j) * h;
      numeric.col(j) = (gyroTransition(e, dt) * q - gyroTransition(-e, dt) * q) / (2.0 * h);
    }
    EXPECT_LT(relativeError(0.5 * dt * rightProductMatrix(q), numeric), 1e-6) << "sample " << i;
  }
}

}  // namespace
}  // namespace headingd::core
