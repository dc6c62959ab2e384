// Heading and its redefinition for lying-down poses (Henriksson §2.5.2, §3.3).
#include "headingd/core/heading_definition.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kPi;
using test::kRadPerDeg;
using test::Random;

TEST(HeadingDefinition, ThesisExample331) {
  // q = (0.649, 0, -0.760, 0) = (cos, sin) of -1.1π/4 about y: tilted backwards past
  // vertical. The x-axis heading flips to ±180°, the redefined heading (of the -z axis, the
  // head) stays at 0°.
  const Quat q = Quat(0.649, 0.0, -0.760, 0.0).normalized();
  EXPECT_NEAR(q.w(), std::cos(-1.1 * kPi / 4.0), 1e-3);
  EXPECT_NEAR(std::abs(headingOf(q)), kPi, 0.5 * kRadPerDeg);
  EXPECT_NEAR(headingOfAxis(q, kDocumentedHeadAxis), 0.0, 0.5 * kRadPerDeg);
  // The exact rotation gives the same, to rounding.
  const Quat exact(Eigen::AngleAxisd(-1.1 * kPi / 2.0, Vec3::UnitY()));
  EXPECT_NEAR(std::abs(headingOf(exact)), kPi, 1e-9);
  EXPECT_NEAR(headingOfAxis(exact, kDocumentedHeadAxis), 0.0, 1e-9);
}

TEST(HeadingDefinition, HeadingIsTheYawOfTheXAxis) {
  Random rng(41);
  for (int i = 0; i < 200; ++i) {
    const double yaw = rng.uniform(-kPi, kPi);
    const Quat q = test::fromYawPitchRoll(yaw, rng.uniform(-1.4, 1.4), rng.uniform(-kPi, kPi));
    EXPECT_LT(test::angleDifference(headingOf(q), yaw), 1e-9);
    // Independently: the body x-axis in NED, projected on the horizontal plane.
    const Vec3 x_n = q * Vec3::UnitX();
    EXPECT_LT(test::angleDifference(headingOf(q), std::atan2(x_n.y(), x_n.x())), 1e-9);
  }
}

TEST(HeadingDefinition, RedefinedHeadingIsTheHeadingOfTheHead) {
  // Definition 3.3.1: the heading of the body's -z axis (the head).
  Random rng(42);
  for (int i = 0; i < 200; ++i) {
    const Quat q = rng.unitQuat();
    const Vec3 head_n = q * Vec3(0.0, 0.0, -1.0);
    if (head_n.head<2>().norm() < 0.05) continue;  // head vertical: no heading to compare
    EXPECT_LT(test::angleDifference(headingOfAxis(q, kDocumentedHeadAxis), std::atan2(head_n.y(), head_n.x())), 1e-9)
        << i;
  }
  // Lying on the back, head pointing east: ψ_rd = 90°.
  const Quat lying_east = headingRotation(kPi / 2) * Quat(Eigen::AngleAxisd(-kPi / 2, Vec3::UnitY()));
  EXPECT_NEAR(headingOfAxis(lying_east, kDocumentedHeadAxis), kPi / 2, 1e-12);
}

TEST(HeadingDefinition, AnyHeadAxisIsEq311WithXTurnedOntoIt) {
  // Eq. 3.11: ψ_rd = heading of q ⊗ q_y, q_y (eq. 3.10) taking x onto -z. For any head axis a
  // the same holds with the rotation that takes x onto a.
  Random rng(44);
  const double h = std::sqrt(0.5);
  for (int i = 0; i < 200; ++i) {
    const Quat q = rng.unitQuat();
    if ((q * kDocumentedHeadAxis).head<2>().norm() > 0.05) {
      EXPECT_LT(test::angleDifference(headingOfAxis(q, kDocumentedHeadAxis), headingOf(q * Quat(h, 0.0, h, 0.0))), 1e-9)
          << i;
    }
    const Vec3 a = rng.unitQuat() * Vec3::UnitX();
    const Quat q_xa = Quat::FromTwoVectors(Vec3::UnitX(), a);
    if ((q * a).head<2>().norm() < 0.05) continue;  // axis vertical: no heading to compare
    EXPECT_LT(test::angleDifference(headingOfAxis(q, a), headingOf(q * q_xa)), 1e-9) << i;
    EXPECT_NEAR(headHeight(q, a), -(q * a).z(), 1e-15) << i;
  }
  // The x axis as the head: the heading of definition 2.5.1.
  const Quat q = test::fromYawPitchRoll(0.7, 0.2, -0.4);
  EXPECT_NEAR(headingOfAxis(q, Vec3::UnitX()), headingOf(q), 1e-12);
}

TEST(HeadingDefinition, HeadHeight) {
  EXPECT_NEAR(headHeight(Quat::Identity(), kDocumentedHeadAxis), 1.0, 1e-15);
  EXPECT_NEAR(headHeight(headingRotation(2.0), kDocumentedHeadAxis), 1.0, 1e-15);  // heading does not matter
  const Vec3 head = kDocumentedHeadAxis;
  EXPECT_NEAR(headHeight(Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY())), head), 0.0, 1e-15);   // lying flat
  EXPECT_NEAR(headHeight(Quat(Eigen::AngleAxisd(-kPi / 2, Vec3::UnitX())), head), 0.0, 1e-15);  // on the side
  EXPECT_NEAR(headHeight(Quat(Eigen::AngleAxisd(kPi, Vec3::UnitX())), head), -1.0, 1e-15);      // upside down
  // In general, for -z: element (3,3) of R(q) (eq. 3.12 written out; eq. 3.13 up to its sign).
  Random rng(43);
  for (int i = 0; i < 100; ++i) {
    const Quat q = rng.unitQuat();
    const double r33 = q.w() * q.w() - q.x() * q.x() - q.y() * q.y() + q.z() * q.z();
    EXPECT_NEAR(headHeight(q, kDocumentedHeadAxis), r33, 1e-14);
  }
}

TEST(HeadingDefinitionSelector, HysteresisBetweenEnterAndLeave) {
  HeadingDefinitionSelector s(0.6, 0.7);
  // The head height h of eq. 3.12, sample by sample:
  EXPECT_FALSE(s.redefined());
  EXPECT_FALSE(s.update(0.9, 0.01));
  EXPECT_FALSE(s.update(0.65, 0.01));  // between: stays with ψ
  EXPECT_TRUE(s.update(0.55, 0.01));   // below 0.6: ψ_rd
  EXPECT_TRUE(s.update(0.65, 0.01));   // between: stays with ψ_rd
  EXPECT_TRUE(s.update(0.0, 0.01));
  EXPECT_TRUE(s.update(-0.9, 0.01));
  EXPECT_TRUE(s.update(0.69, 0.01));
  EXPECT_FALSE(s.update(0.75, 0.01));  // above 0.7: ψ again
  EXPECT_FALSE(s.update(0.61, 0.01));
  EXPECT_FALSE(s.redefined());
}

TEST(HeadingDefinitionSelector, EntersOnlyOnceTheHeadHasStayedLowLongEnough) {
  HeadingDefinitionSelector s(0.6, 0.7, 2.0);
  // A swung phone: h dips below 0.6 for 1.5 s at a time (150 samples of 10 ms), then rises.
  for (int swing = 0; swing < 5; ++swing) {
    for (int k = 0; k < 150; ++k) EXPECT_FALSE(s.update(0.3, 0.01));
    EXPECT_FALSE(s.update(0.65, 0.01));  // between enter and leave: the time below starts over
  }
  // Lying down: below for 2 s, then redefined until h is back above 0.7.
  for (int k = 0; k < 195; ++k) EXPECT_FALSE(s.update(0.1, 0.01));
  for (int k = 0; k < 10; ++k) s.update(0.1, 0.01);  // 2 s reached within these (rounding)
  EXPECT_TRUE(s.redefined());
  EXPECT_TRUE(s.update(0.65, 0.01));
  EXPECT_FALSE(s.update(0.75, 0.01));  // getting up leaves at once
  // Samples without a time step (start, gap) do not count as time below.
  for (int k = 0; k < 1000; ++k) EXPECT_FALSE(s.update(0.1, 0.0));
}

}  // namespace
}  // namespace headingd::core
