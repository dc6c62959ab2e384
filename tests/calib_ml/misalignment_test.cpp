// K&S §6.2 eq. 27: a known misalignment and dip are recovered from exact data, from any of
// several tilts and headings.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/calib/ml/misalignment.hpp"

namespace headingd::calib {
namespace {

using core::Mat3;
using core::Quat;
using core::Vec3;

TEST(Misalignment, RecoversRotationAndDipFromExactData) {
  const double dip = 1.1;
  const Vec3 m_n(std::cos(dip), 0.0, std::sin(dip));
  const Mat3 r_d = (Eigen::AngleAxisd(0.7, Vec3(1.0, -2.0, 0.5).normalized())).toRotationMatrix();
  std::vector<Vec3> u, v;
  for (int i = 0; i < 400; ++i) {
    const double t = 0.05 * i;
    const Quat q_nb(Eigen::AngleAxisd(1.3 * t, Vec3::UnitZ()) *
                    Eigen::AngleAxisd(0.9 * std::sin(0.7 * t), Vec3::UnitY()) *
                    Eigen::AngleAxisd(2.1 * t, Vec3::UnitX()));
    const Vec3 m_b = q_nb.conjugate() * m_n;
    v.push_back(q_nb.conjugate() * Vec3::UnitZ());
    u.push_back(r_d * m_b);  // eq. 26b: m_b = R_Dᵀ u
  }
  const MisalignmentEstimate e = estimateMisalignment(u, v);
  EXPECT_LT((e.rotation - r_d).norm(), 1e-6);
  EXPECT_NEAR(e.dip_rad, dip, 1e-8);
  EXPECT_LT(e.rms_residual, 1e-8);
}

// A slow wobble about a near-upright attitude (a few seconds in a hand): eq. 27 then has a
// minimum for each sign of m_z (dip_sign.hpp). The expected sign picks the true one whichever
// fits better, and the other sign gives the mirror.
TEST(Misalignment, ExpectedDipSignPicksBetweenTheMirrorMinima) {
  const double dip = 1.2;
  const Vec3 m_n(std::cos(dip), 0.0, std::sin(dip));
  const Mat3 r_d = (Eigen::AngleAxisd(0.4, Vec3(0.3, 1.0, -0.2).normalized())).toRotationMatrix();
  std::vector<Vec3> u, v;
  for (int i = 0; i < 300; ++i) {
    const double t = 0.01 * i;
    const Quat q_nb(Eigen::AngleAxisd(0.8 * t, Vec3::UnitZ()) *
                    Eigen::AngleAxisd(0.3 * std::sin(2.0 * t), Vec3::UnitY()) *
                    Eigen::AngleAxisd(0.25 * std::cos(1.5 * t), Vec3::UnitX()));
    v.push_back(q_nb.conjugate() * Vec3::UnitZ());
    u.push_back(r_d * (q_nb.conjugate() * m_n));
  }
  const std::vector<MisalignmentEstimate> minima = misalignmentMinima(u, v);
  ASSERT_GE(minima.size(), 1u);
  for (std::size_t i = 1; i < minima.size(); ++i) EXPECT_GE(minima[i].rms_residual, minima[i - 1].rms_residual);

  const MisalignmentEstimate down = estimateMisalignment(u, v, DipSign::kDown);
  EXPECT_GT(down.field_down, 0.0);
  EXPECT_NEAR(down.dip_rad, dip, 1e-6);
  EXPECT_LT((down.rotation - r_d).norm(), 1e-5);

  const MisalignmentEstimate up = estimateMisalignment(u, v, DipSign::kUp);
  bool has_negative = false;
  for (const MisalignmentEstimate& m : minima) has_negative = has_negative || m.field_down < 0.0;
  ASSERT_TRUE(has_negative);  // measured: m_z +0.932 (exact), -0.970, +0.742
  EXPECT_LT(up.field_down, 0.0);
}

TEST(DipSign, FromTheExpectedDip) {
  EXPECT_EQ(dipSignOf(72.2 * 3.14159265358979 / 180.0), DipSign::kDown);
  EXPECT_EQ(dipSignOf(-60.0 * 3.14159265358979 / 180.0), DipSign::kUp);
  EXPECT_EQ(dipSignOf(2.0 * 3.14159265358979 / 180.0), DipSign::kUnknown);  // near the magnetic equator
  EXPECT_EQ(dipSignOf(std::nan("")), DipSign::kUnknown);
  EXPECT_TRUE(dipAgrees(0.5, DipSign::kDown));
  EXPECT_FALSE(dipAgrees(-0.5, DipSign::kDown));
  EXPECT_TRUE(dipAgrees(-0.5, DipSign::kUnknown));
}

TEST(Misalignment, RejectsMismatchedOrTooShortInput) {
  std::vector<Vec3> a(5, Vec3::UnitX()), b(6, Vec3::UnitZ());
  EXPECT_THROW(estimateMisalignment(a, b), CalibrationError);
  EXPECT_THROW(estimateMisalignment(a, std::vector<Vec3>(5, Vec3::UnitZ())), CalibrationError);
}

}  // namespace
}  // namespace headingd::calib
