// The EKF's generic update (AttitudeEkf::update) with a measurement model, and the two updates
// built on it: MAU against the WMM's field (magnetic_attitude_update.hpp) and the QSF update
// (quasi_static_field_update.hpp). Each corrects what it is meant to and leaves the rest.
#include <gtest/gtest.h>

#include <cmath>

#include "headingd/core/attitude_ekf.hpp"
#include "headingd/core/magnetic_attitude_update.hpp"
#include "headingd/core/quasi_static_field_update.hpp"
#include "headingd/core/reference_vector_model.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::kRadPerDeg;

constexpr double kGravity = 9.81;
const Vec3 kFieldNed(19.0, 0.0, 47.0);  // µT, magnetic NED: 51 µT at a dip of 68°

Quat attitude(double roll_deg, double pitch_deg, double yaw_deg) {
  return Quat(Eigen::AngleAxisd(yaw_deg * kRadPerDeg, Vec3::UnitZ()) *
              Eigen::AngleAxisd(pitch_deg * kRadPerDeg, Vec3::UnitY()) *
              Eigen::AngleAxisd(roll_deg * kRadPerDeg, Vec3::UnitX()));
}

// The angle between two attitudes' down axes (tilt) and the difference of their yaws.
double tiltErrorDeg(const Quat& a, const Quat& b) {
  const Vec3 down_a = a.conjugate() * Vec3::UnitZ(), down_b = b.conjugate() * Vec3::UnitZ();
  return std::atan2(down_a.cross(down_b).norm(), down_a.dot(down_b)) / kRadPerDeg;
}
double yawErrorDeg(const Quat& a, const Quat& b) {
  return std::remainder(yawZyx(a) - yawZyx(b), 2 * M_PI) / kRadPerDeg;
}

// An EKF at `estimate` whose covariance is in its tilt form (one gravity update has run) with
// a tilt sigma of about sigma_deg.
AttitudeEkf ekfAt(const Quat& estimate, double sigma_deg) {
  AttitudeEkf ekf;
  ekf.setAttitude(estimate);
  const double s = 0.5 * sigma_deg * kRadPerDeg;  // the 4-D state moves by half the angle
  ekf.setCovariance(s * s * Mat4::Identity());
  const Vec3 gravity_seen = estimate.conjugate() * Vec3(0.0, 0.0, -kGravity);
  ekf.updateGravity(gravity_seen, 100.0, kGravity);  // consistent and nearly uninformative
  return ekf;
}

Linearised<3> fieldMeasurement(const AttitudeEkf& ekf, const Quat& truth, const Vec3& reference_ned, double sigma) {
  NavigationState x;
  x.q_nb = ekf.attitude();
  return ReferenceVectorModel{reference_ned, sigma}.linearise(x, truth.conjugate() * kFieldNed);
}

TEST(AttitudeEkfUpdate, ATiltOnlyUpdateCorrectsTheTiltAndLeavesTheYaw) {
  const Quat truth = attitude(10.0, -5.0, 40.0);
  AttitudeEkf ekf = ekfAt(attitude(14.0, -5.0, 40.0), 5.0);
  const double yaw_before = yawZyx(ekf.attitude());
  ASSERT_NEAR(tiltErrorDeg(ekf.attitude(), truth), 4.0, 0.1);
  const auto result = ekf.update(fieldMeasurement(ekf, truth, kFieldNed, 0.2), 2.0 * kRadPerDeg, AttitudeAxes{}, 1e9);
  ASSERT_TRUE(result.applied);
  EXPECT_LT(tiltErrorDeg(ekf.attitude(), truth), 0.5);
  EXPECT_NEAR(result.turn_rad.z(), 0.0, 1e-12);
  // Nothing about down; zyx yaw moves a little with the tilt (second order: tilt × roll).
  EXPECT_NEAR(yawZyx(ekf.attitude()), yaw_before, 0.5 * kRadPerDeg);
  EXPECT_LT(ekf.tiltCovariance().trace(), 2.0 * std::pow(5.0 * kRadPerDeg, 2));  // it has learned
}

TEST(AttitudeEkfUpdate, AHeadingOnlyUpdateCorrectsTheHeadingAndLeavesTheTilt) {
  const Quat truth = attitude(10.0, -5.0, 40.0);
  // The tilt's own uncertainty limits what the field says of the heading (by tan(dip) per unit of
  // tilt): a well-known tilt here.
  AttitudeEkf ekf = ekfAt(attitude(10.0, -5.0, 46.0), 0.1);
  const Eigen::Matrix2d tilt_before = ekf.tiltCovariance();
  const auto result = ekf.update(fieldMeasurement(ekf, truth, kFieldNed, 0.2), 10.0 * kRadPerDeg,
                                 AttitudeAxes{.tilt = false, .heading = true}, 1e9);
  ASSERT_TRUE(result.applied);
  EXPECT_NEAR(yawErrorDeg(ekf.attitude(), truth), 0.0, 0.3);
  EXPECT_NEAR(result.turn_rad.x(), 0.0, 1e-12);
  EXPECT_NEAR(result.turn_rad.y(), 0.0, 1e-12);
  EXPECT_EQ(ekf.tiltCovariance(), tilt_before);
  EXPECT_LT(result.heading_variance_rad2, std::pow(1.0 * kRadPerDeg, 2));
}

TEST(AttitudeEkfUpdate, TheGravityModelThroughTheGenericUpdateIsTheGravityUpdate) {
  // Henriksson eq. 3.5 as a ReferenceVectorModel through update() and through the EKF's own
  // closed-form gravity update: one estimate, one covariance (gravity sees no heading, so
  // considering the heading changes nothing).
  const Quat truth = attitude(12.0, -7.0, 200.0);
  const Vec3 accel = truth.conjugate() * Vec3(0.0, 0.0, -kGravity) + Vec3(0.05, -0.02, 0.03);
  AttitudeEkf specialised = ekfAt(attitude(15.0, -9.0, 200.0), 3.0);
  AttitudeEkf generic = specialised;
  specialised.updateGravity(accel, 0.3, kGravity);
  NavigationState x;
  x.q_nb = generic.attitude();
  const ReferenceVectorModel gravity{Vec3(0.0, 0.0, -kGravity), 0.3};
  ASSERT_TRUE(generic.update(gravity.linearise(x, accel), 5.0 * kRadPerDeg, AttitudeAxes{}, 1e9).applied);
  EXPECT_LT(generic.attitude().angularDistance(specialised.attitude()), 1e-4);
  EXPECT_TRUE(generic.tiltCovariance().isApprox(specialised.tiltCovariance(), 1e-3));
}

TEST(AttitudeEkfUpdate, TheGateRejectsAnInnovationBeyondItAndChangesNothing) {
  const Quat truth = attitude(0.0, 0.0, 0.0);
  AttitudeEkf ekf = ekfAt(attitude(30.0, 0.0, 0.0), 1.0);  // far beyond its 1° sigma
  const Vec4 before = ekf.state();
  const auto result = ekf.update(fieldMeasurement(ekf, truth, kFieldNed, 0.2), 1.0 * kRadPerDeg, AttitudeAxes{}, 16.27);
  EXPECT_FALSE(result.applied);
  EXPECT_GT(result.innovation_nis, 16.27);
  EXPECT_EQ(ekf.state(), before);
}

TEST(AttitudeEkfUpdate, NothingIsUpdatedWhileTheCovarianceIsStillGeneral) {
  AttitudeEkf ekf;  // start-up: P = 1000 I, not yet about the NED axes
  const auto result = ekf.update(fieldMeasurement(ekf, attitude(5, 0, 0), kFieldNed, 0.2), 0.1, AttitudeAxes{}, 1e9);
  EXPECT_FALSE(result.applied);
  EXPECT_EQ(ekf.state(), Vec4(1.0, 0.0, 0.0, 0.0));
}

MagneticAttitudeUpdateParams mauParams() {
  return {.noise_uT = 2.0, .interval_s = 1.0, .verify_max_rad = 0.1, .max_nis = 16.27};
}

TEST(MagneticAttitudeUpdate, TheWmmFieldCorrectsTheTiltOncePerInterval) {
  const Quat truth = attitude(-20.0, 15.0, 120.0);
  AttitudeEkf ekf = ekfAt(attitude(-17.0, 13.0, 120.0), 5.0);
  MagneticAttitudeUpdate mau(mauParams());
  mau.setReference(kFieldNed.norm(), std::atan2(kFieldNed.z(), kFieldNed.x()));
  const Vec3 measured = truth.conjugate() * kFieldNed;
  int applied = 0;
  for (int i = 0; i < 100; ++i) applied += mau.update(ekf, measured, 0.1, 2.0 * kRadPerDeg) ? 1 : 0;  // 10 s
  EXPECT_EQ(applied, 10);
  EXPECT_EQ(mau.counters().applied, 10u);
  EXPECT_LT(tiltErrorDeg(ekf.attitude(), truth), 0.5);
}

TEST(MagneticAttitudeUpdate, WithoutAReferenceOrWhenOffNothingHappens) {
  AttitudeEkf ekf = ekfAt(attitude(3.0, 0.0, 0.0), 5.0);
  const Vec4 before = ekf.state();
  MagneticAttitudeUpdate no_reference(mauParams());
  EXPECT_FALSE(no_reference.update(ekf, kFieldNed, 2.0, 0.1));
  auto off_params = mauParams();
  off_params.noise_uT = 0.0;
  MagneticAttitudeUpdate off(off_params);
  off.setReference(51.0, 1.2);
  EXPECT_FALSE(off.update(ekf, kFieldNed, 2.0, 0.1));
  EXPECT_EQ(ekf.state(), before);
}

TEST(MagneticAttitudeUpdate, AnAttitudeTheMagneticFrameDoesNotConfirmIsUndone) {
  const Quat truth = attitude(0.0, 0.0, 0.0);
  AttitudeEkf ekf = ekfAt(attitude(4.0, 0.0, 0.0), 5.0);
  const Vec4 before = ekf.state();
  auto params = mauParams();
  params.verify_max_rad = 1e-6;  // no corrected attitude can be this close with 2 µT of noise
  MagneticAttitudeUpdate mau(params);
  mau.setReference(kFieldNed.norm(), std::atan2(kFieldNed.z(), kFieldNed.x()));
  EXPECT_FALSE(mau.update(ekf, truth.conjugate() * kFieldNed, 1.0, 2.0 * kRadPerDeg));
  EXPECT_EQ(mau.counters().rejected_by_verification, 1u);
  EXPECT_EQ(ekf.state(), before);
}

QuasiStaticFieldUpdateParams qsfParams() { return {.noise_uT = 1.0, .residual_hard_iron_uT = 0.0, .max_nis = 16.27}; }

TEST(QuasiStaticFieldUpdate, HoldsTheHeadingToThePeriodsStartWhileTheFieldIsSetAside) {
  // A disturbed but static field: wrong in value, constant in NED.
  const Vec3 disturbed_ned = kFieldNed + Vec3(-12.0, 25.0, 8.0);
  const Quat truth = attitude(5.0, 5.0, 70.0);
  AttitudeEkf ekf = ekfAt(truth, 0.1);
  QuasiStaticFieldUpdate qsf(qsfParams());
  const Vec3 measured = truth.conjugate() * disturbed_ned;
  constexpr double kRateSigma = 0.05;  // rad/s: 2.9° of drift in one second
  // The gyro's frame: where the gyro alone carries the attitude (the EKF follows it between updates).
  Quat gyro = ekf.attitude();
  EXPECT_EQ(qsf.update(ekf, measured, gyro, true, true, 0.01, kRateSigma), 0.0);  // the period's reference
  // Over a second the gyro drifts the estimate by 3° about down; the field has not turned.
  ekf.turnHeading(3.0 * kRadPerDeg);
  gyro = headingRotation(3.0 * kRadPerDeg) * gyro;
  EXPECT_EQ(qsf.update(ekf, measured, gyro, true, /*set_aside=*/false, 0.5, kRateSigma), 0.0);  // the observer's
  // One sample at 1 µT says the heading to about 2°; twenty of them to a fraction of a degree.
  const double first_turn = qsf.update(ekf, measured, gyro, true, true, 0.5, kRateSigma);
  EXPECT_LT(first_turn, -1.5 * kRadPerDeg);
  for (int i = 1; i < 20; ++i) qsf.update(ekf, measured, gyro, true, true, 0.01, kRateSigma);
  EXPECT_NEAR(yawErrorDeg(ekf.attitude(), truth), 0.0, 0.1);
  EXPECT_EQ(qsf.counters().applied, 20u);
  // The period ends: the next one takes a new reference rather than the old.
  EXPECT_EQ(qsf.update(ekf, measured, gyro, false, true, 0.01, kRateSigma), 0.0);
  ekf.turnHeading(3.0 * kRadPerDeg);
  gyro = headingRotation(3.0 * kRadPerDeg) * gyro;
  EXPECT_EQ(qsf.update(ekf, measured, gyro, true, true, 0.01, kRateSigma), 0.0);
  EXPECT_NEAR(qsf.update(ekf, measured, gyro, true, true, 0.01, kRateSigma), 0.0, 1e-9);
}

TEST(QuasiStaticFieldUpdate, TheEkfsTiltCorrectionsAreNotTakenForHeadingDrift) {
  // Standing in a static field, gravity corrects the EKF's tilt by 0.5° during the period: the
  // reference, taken with the old tilt, then points elsewhere by about 0.5°·tan(dip) in heading.
  // Compared through the gyro's frame (which did not move) there is nothing to correct.
  const Quat truth = attitude(0.0, 0.0, 40.0);
  AttitudeEkf ekf = ekfAt(attitude(0.5, 0.0, 40.0), 0.1);
  QuasiStaticFieldUpdate qsf(qsfParams());
  const Vec3 measured = truth.conjugate() * kFieldNed;
  const Quat gyro = Quat::Identity();
  qsf.update(ekf, measured, gyro, true, true, 0.01, 0.05);
  ekf.setAttitude(truth);  // gravity's correction of the tilt
  for (int i = 0; i < 20; ++i) qsf.update(ekf, measured, gyro, true, true, 0.01, 0.05);
  EXPECT_LT(std::abs(yawErrorDeg(ekf.attitude(), truth)), 0.05);
}

TEST(QuasiStaticFieldUpdate, AFieldThatMovedFurtherThanTheGyroCanDriftIsRejected) {
  const Quat truth = attitude(0.0, 0.0, 0.0);
  AttitudeEkf ekf = ekfAt(truth, 1.0);
  QuasiStaticFieldUpdate qsf(qsfParams());
  qsf.update(ekf, truth.conjugate() * kFieldNed, Quat::Identity(), true, true, 0.01, 0.01);
  // 30° in a second, where the gyro's rate error allows 0.6°: the field moved, not the heading.
  const Vec3 moved = attitude(0.0, 0.0, 30.0).conjugate() * kFieldNed;
  const Vec4 before = ekf.state();
  EXPECT_EQ(qsf.update(ekf, moved, Quat::Identity(), true, true, 1.0, 0.01), 0.0);
  EXPECT_EQ(qsf.counters().rejected_by_gate, 1u);
  EXPECT_EQ(ekf.state(), before);
}

TEST(QuasiStaticFieldUpdate, TurningWithinThePeriodWeighsTheResidualHardIron) {
  // A residual hard iron of 3 µT fixed in sensor axes: after a 90° turn it has moved by 4 µT in
  // NED, which a white noise of 1 µT would take into the heading as ~10°.
  const Vec3 residual_s(3.0, 0.0, 0.0);
  const Quat start = attitude(0.0, 0.0, 0.0), turned = attitude(0.0, 0.0, 90.0);
  for (const double allowance : {0.0, 3.0}) {
    AttitudeEkf ekf = ekfAt(start, 0.1);
    auto params = qsfParams();
    params.residual_hard_iron_uT = allowance;
    QuasiStaticFieldUpdate qsf(params);
    qsf.update(ekf, start.conjugate() * kFieldNed + residual_s, start, true, true, 0.01, 0.05);
    ekf.setAttitude(turned);  // the gyro's turn, exact
    qsf.update(ekf, turned.conjugate() * kFieldNed + residual_s, turned, true, true, 1.0, 0.05);
    const double error_deg = std::abs(yawErrorDeg(ekf.attitude(), turned));
    if (allowance == 0.0) {
      EXPECT_GT(error_deg, 2.0);
    } else {
      EXPECT_LT(error_deg, 1.0);
    }
  }
}

}  // namespace
}  // namespace headingd::core
