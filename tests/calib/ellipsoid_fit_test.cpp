// Kok & Schön §6.1 ellipsoid fit against the simulator's truth (Table 2 distortions).
#include "headingd/calib/ellipsoid_fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "calib_test_support.hpp"

namespace headingd::calib_test {
namespace {

using core::Mat3;
using core::Vec3;

// D is recoverable only up to a rotation (eq. 25): compare D Dᵀ, relative to its size.
double relativeShapeError(const Mat3& d_fit, const Mat3& d_true) {
  const Mat3 a = d_fit * d_fit.transpose(), b = d_true * d_true.transpose();
  return (a - b).norm() / b.norm();
}

TEST(EllipsoidFit, RecoversTableTwoDistortionsFromTheShortRotation) {
  // 400 samples, Kok & Schön §8's recording: three turns, one about each axis, 1.6 µT noise.
  // Three circles pin the ellipsoid down only loosely (condition ~40, one seed in ten ~90
  // and far off): the median over 10 seeds is checked, and every fit must be usable.
  std::vector<double> shape, offset;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const sim::SimResult& r = simulated("calib-rotation", seed);
    const calib::EllipsoidFit fit = calib::fitEllipsoid(magOf(r), fieldNorm(r));
    SCOPED_TRACE("seed " + std::to_string(seed) + " coverage " + std::to_string(fit.coverage));
    shape.push_back(relativeShapeError(fit.D, r.mag.distortion));
    offset.push_back((fit.offset_uT - r.mag.offset).norm());
    EXPECT_LT(fit.residual_rms_uT, 3.0);
    EXPECT_GT(fit.coverage, 0.25);
    EXPECT_GT(fit.condition_number, 10.0);
    // The fitted D is symmetric positive definite.
    EXPECT_LT((fit.D - fit.D.transpose()).norm(), 1e-9);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat3>(fit.D).eigenvalues().minCoeff(), 0.0);
  }
  std::sort(shape.begin(), shape.end());
  std::sort(offset.begin(), offset.end());
  EXPECT_LT(shape[5], 0.10);  // relative error of D Dᵀ, D_ii up to 1.5, skew up to 30°
  EXPECT_LT(offset[5], 2.5);  // µT; the offsets drawn are up to ±52 µT per axis
}

TEST(EllipsoidFit, HandHeldRecordingIsTighter) {
  for (std::uint64_t seed : {1u, 2u}) {
    const sim::SimResult& r = simulated("calib-rotation-long", seed);
    const calib::EllipsoidFit fit = calib::fitEllipsoid(magOf(r), fieldNorm(r));
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_LT(relativeShapeError(fit.D, r.mag.distortion), 0.01);
    EXPECT_LT((fit.offset_uT - r.mag.offset).norm(), 0.5);
    EXPECT_GT(fit.coverage, 0.6);
    EXPECT_NEAR(fit.residual_rms_uT, std::sqrt(1e-3) * fieldNorm(r), 0.5);  // the noise itself
  }
}

TEST(EllipsoidFit, PaperEstimateAloneIsClose) {
  const sim::SimResult& r = simulated("calib-rotation-long", 3);
  calib::EllipsoidFitOptions o;
  o.geometric_refinement = false;
  const calib::EllipsoidFit fit = calib::fitEllipsoid(magOf(r), fieldNorm(r), o);
  EXPECT_LT(relativeShapeError(fit.D, r.mag.distortion), 0.03);
  EXPECT_LT((fit.offset_uT - r.mag.offset).norm(), 1.5);
}

TEST(EllipsoidFit, ExactDataGivesExactAnswer) {
  // Noise-free points of a known ellipsoid: D symmetric, so it comes back itself.
  Mat3 d;
  d << 1.2, 0.1, -0.05, 0.1, 0.8, 0.02, -0.05, 0.02, 1.05;
  const Vec3 o(20.0, -35.0, 12.0);
  std::vector<Vec3> y;
  for (int i = 0; i < 500; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / 500.0, phi = 2.399963 * i, r = std::sqrt(1.0 - z * z);
    y.push_back(d * (50.0 * Vec3(r * std::cos(phi), r * std::sin(phi), z)) + o);
  }
  const calib::EllipsoidFit fit = calib::fitEllipsoid(y, 50.0);
  EXPECT_LT((fit.D - d).norm(), 1e-6);
  EXPECT_LT((fit.offset_uT - o).norm(), 1e-5);
  EXPECT_LT(fit.residual_rms_uT, 1e-5);
  EXPECT_GT(fit.coverage, 0.99);
}

TEST(EllipsoidFit, TooLittleRotationIsAClearError) {
  // Turning about one axis only: the data lie on one ellipse (a plane), not an ellipsoid.
  const Mat3 d = Mat3::Identity();
  std::vector<Vec3> y;
  for (int i = 0; i < 300; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 300.0;
    const double tilt = 0.02 * std::sin(7.0 * a);  // a little wobble, as a hand makes
    y.push_back(d * Vec3(15.0 * std::cos(a), 15.0 * std::sin(a), 50.0 + 5.0 * tilt) + Vec3(3.0, 4.0, 5.0));
  }
  try {
    (void)calib::fitEllipsoid(y, 52.0);
    FAIL() << "expected a CalibrationError";
  } catch (const calib::CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("% of the sphere"), std::string::npos) << e.what();
  }
}

TEST(EllipsoidFit, StationaryDataAndBadInputAreErrors) {
  std::vector<Vec3> still(100, Vec3(10.0, 20.0, 30.0));
  EXPECT_THROW((void)calib::fitEllipsoid(still, 50.0), calib::CalibrationError);
  std::vector<Vec3> few(5, Vec3(1.0, 2.0, 3.0));
  EXPECT_THROW((void)calib::fitEllipsoid(few, 50.0), calib::CalibrationError);
  std::vector<Vec3> nan(100, Vec3(1.0, std::nan(""), 3.0));
  EXPECT_THROW((void)calib::fitEllipsoid(nan, 50.0), calib::CalibrationError);
  std::vector<Vec3> ok(100, Vec3(1.0, 2.0, 3.0));
  EXPECT_THROW((void)calib::fitEllipsoid(ok, -1.0), calib::CalibrationError);
}

TEST(SphereCoverage, CountsCells) {
  std::vector<Vec3> one(10, Vec3::UnitX());
  EXPECT_NEAR(calib::sphereCoverage(one), 1.0 / 200.0, 1e-12);
  EXPECT_EQ(calib::sphereCoverage({}), 0.0);
}

}  // namespace
}  // namespace headingd::calib_test
