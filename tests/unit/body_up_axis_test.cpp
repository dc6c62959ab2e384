// The person's up axis in sensor axes, learned while walking (body_up_axis.hpp).
#include "headingd/core/body_up_axis.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "headingd/core/heading_definition.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kPi;
using test::kRadPerDeg;

constexpr double kDt = 0.01;  // 100 Hz

// The defaults: τ 30 s, 5 s to learn, 60 s to learn afresh, upright above h = 0.7, lying below 0.6.
BodyUpAxisParams params(double time_constant_s = 30.0) {
  return {kDocumentedHeadAxis, time_constant_s, 5.0, 60.0, 0.7, 0.6};
}

double angleBetween(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// A walking person's body (x forward, z down) at time t: upright, swaying 3° in pitch and roll
// at the step frequency and turning slowly, so that every heading is seen.
Quat walkingBody(double t) {
  const double step = 2.0 * kPi * 1.9 * t;
  return test::fromYawPitchRoll(0.3 * t, 3.0 * kRadPerDeg * std::sin(step), 3.0 * kRadPerDeg * std::sin(0.5 * step));
}

// Feeds `seconds` of walking with the sensor mounted q_bs (sensor to body).
void walk(BodyUpAxis& up, const Quat& q_bs, double seconds, double t0 = 0.0) {
  for (double t = t0; t < t0 + seconds; t += kDt) up.update(walkingBody(t) * q_bs, true, kDt);
}

// Mountings: documented, flat with z up (a phone screen-up), x up (upright in a pocket), upside
// down in a pocket, and an arbitrary tilt.
const Quat kMountings[] = {
    Quat::Identity(),
    Quat(Eigen::AngleAxisd(kPi, Vec3::UnitX())),
    Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY())),
    Quat(Eigen::AngleAxisd(-kPi / 2, Vec3::UnitY())) * Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX())),
    test::fromYawPitchRoll(0.4, -0.7, 2.2),
};

TEST(BodyUpAxis, StartsAtTheDefaultAndLearnsAnyMountingFromWalking) {
  for (const Quat& q_bs : kMountings) {
    BodyUpAxis up(params());
    EXPECT_FALSE(up.learned());
    EXPECT_EQ(up.axis(), kDocumentedHeadAxis);
    walk(up, q_bs, 60.0);
    ASSERT_TRUE(up.learned());
    // The body's -z (its head) in sensor axes: the sway averages out.
    const Vec3 head_s = q_bs.conjugate() * kDocumentedHeadAxis;
    EXPECT_LT(angleBetween(up.axis(), head_s), 0.5 * kRadPerDeg) << q_bs.coeffs().transpose();
    EXPECT_NEAR(up.axis().norm(), 1.0, 1e-12);
  }
}

TEST(BodyUpAxis, ReplacesTheDefaultOnlyAfterTheMinimumWalkingTime) {
  const Quat flat_z_up(Eigen::AngleAxisd(kPi, Vec3::UnitX()));
  BodyUpAxis up(params());
  walk(up, flat_z_up, 4.9);
  EXPECT_FALSE(up.learned());
  EXPECT_EQ(up.axis(), kDocumentedHeadAxis);
  walk(up, flat_z_up, 0.2, 4.9);
  EXPECT_TRUE(up.learned());
  // The running-mean start: already right after a few seconds, not pulled towards the default.
  EXPECT_LT(angleBetween(up.axis(), Vec3::UnitZ()), 2.0 * kRadPerDeg);
}

TEST(BodyUpAxis, HeldWhileThePersonDoesNotWalk) {
  const Quat flat_z_up(Eigen::AngleAxisd(kPi, Vec3::UnitX()));
  BodyUpAxis up(params());
  walk(up, flat_z_up, 20.0);
  const Vec3 learned = up.axis();
  // Lying on the back for a minute (body pitched up 90°): not walking, nothing learned.
  const Quat lying = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY())) * flat_z_up;
  for (int k = 0; k < 6000; ++k) up.update(lying, false, kDt);
  EXPECT_EQ(up.axis(), learned);
  // Samples that were not integrated (dt = 0: the first, after a gap) teach nothing either.
  up.update(lying, true, 0.0);
  EXPECT_EQ(up.axis(), learned);
}

TEST(BodyUpAxis, FollowsASensorSlippingWithinTheUprightConeWithItsTimeConstant) {
  // A sensor that slips 30° in its mount (h = cos 30° = 0.87: still upright by the old axis).
  const Quat before = Quat::Identity();
  const Quat after(Eigen::AngleAxisd(30.0 * kRadPerDeg, Vec3::UnitY()));
  const double tau = 30.0;
  BodyUpAxis up(params(tau));
  walk(up, before, 120.0);
  walk(up, after, tau, 120.0);
  // After one time constant the mean has gone 1 - 1/e of the way along the chord (a little
  // more than that share of the angle): 19.4° of the 30°.
  const Vec3 old_s = before.conjugate() * kDocumentedHeadAxis;
  const Vec3 new_s = after.conjugate() * kDocumentedHeadAxis;
  const Vec3 chord = std::exp(-1.0) * old_s + (1.0 - std::exp(-1.0)) * new_s;
  EXPECT_NEAR(angleBetween(up.axis(), old_s), angleBetween(chord, old_s), 1.0 * kRadPerDeg);
  walk(up, after, 5.0 * tau, 120.0 + tau);
  EXPECT_LT(angleBetween(up.axis(), new_s), 1.0 * kRadPerDeg);
}

TEST(BodyUpAxis, CrawlingDoesNotTiltIt) {
  // On hands and knees the body's x points down and -z (the head) forward: the accelerations
  // may look like walking, but the person is not upright.
  BodyUpAxis up(params());
  walk(up, Quat::Identity(), 30.0);
  const Vec3 learned = up.axis();
  const Quat crawling_pitch(Eigen::AngleAxisd(-80.0 * kRadPerDeg, Vec3::UnitY()));
  for (double t = 30.0; t < 80.0; t += kDt) up.update(walkingBody(t) * crawling_pitch, true, kDt);
  EXPECT_EQ(up.axis(), learned);
  EXPECT_LT(angleBetween(up.axis(), kDocumentedHeadAxis), 0.5 * kRadPerDeg);
}

TEST(BodyUpAxis, LearnedAfreshWhenTheSensorHasBeenMoved) {
  // A phone moved from the hand (screen-up) to a trouser pocket (x up): 90° away, every
  // walking sample says "lying down" by the old axis.
  const Quat in_hand(Eigen::AngleAxisd(kPi, Vec3::UnitX()));
  const Quat in_pocket(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY()));
  BodyUpAxis up(params());
  walk(up, in_hand, 60.0);
  const Vec3 hand_s = in_hand.conjugate() * kDocumentedHeadAxis;
  const Vec3 pocket_s = in_pocket.conjugate() * kDocumentedHeadAxis;
  EXPECT_LT(angleBetween(up.axis(), hand_s), 0.5 * kRadPerDeg);
  walk(up, in_pocket, 59.0, 60.0);  // less than relearn_after_s: held
  EXPECT_LT(angleBetween(up.axis(), hand_s), 0.5 * kRadPerDeg);
  walk(up, in_pocket, 1.0 + 4.9, 119.0);  // learned afresh, but not yet for 5 s
  EXPECT_LT(angleBetween(up.axis(), hand_s), 0.5 * kRadPerDeg);
  walk(up, in_pocket, 0.2, 124.9);
  EXPECT_TRUE(up.learned());
  EXPECT_LT(angleBetween(up.axis(), pocket_s), 2.0 * kRadPerDeg);
}

TEST(BodyUpAxis, ZeroTimeConstantKeepsTheDefault) {
  BodyUpAxis up(params(0.0));
  walk(up, Quat(Eigen::AngleAxisd(kPi, Vec3::UnitX())), 60.0);
  EXPECT_FALSE(up.learned());
  EXPECT_EQ(up.axis(), kDocumentedHeadAxis);
}

}  // namespace
}  // namespace headingd::core
