// K&S §6.2 eq. 27: a known misalignment and dip are recovered from exact data, from any of
// several tilts and headings.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/calib/misalignment.hpp"

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
    const Quat q_nb(Eigen::AngleAxisd(1.3 * t, Vec3::UnitZ()) * Eigen::AngleAxisd(0.9 * std::sin(0.7 * t), Vec3::UnitY()) *
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

TEST(Misalignment, RejectsMismatchedOrTooShortInput) {
  std::vector<Vec3> a(5, Vec3::UnitX()), b(6, Vec3::UnitZ());
  EXPECT_THROW(estimateMisalignment(a, b), CalibrationError);
  EXPECT_THROW(estimateMisalignment(a, std::vector<Vec3>(5, Vec3::UnitZ())), CalibrationError);
}

}  // namespace
}  // namespace headingd::calib
