// MARU and AGU (rotated_field_update.hpp): a sensor turned by hand in a field that is wrong but
// static teaches the bias filter the gyro's bias, the vertical part included, and so does
// gravity; a baseline over which the field moved in the room is rejected by the gate; a baseline
// never reaches across a pause.
#include <gtest/gtest.h>

#include <cmath>

#include "headingd/core/estimator_params.hpp"
#include "headingd/core/gyro_bias_estimator.hpp"
#include "headingd/core/quasi_static_field.hpp"
#include "headingd/core/rotated_field_update.hpp"
#include "test_support.hpp"

namespace headingd::core {
namespace {

constexpr double kDt = 0.01;
constexpr double kFieldNoiseUT = 0.4;
const Vec3 kTrueBias(0.004, -0.006, 0.015);  // rad/s; 0.86°/s about the sensor's z
// A field 40 µT strong pointing 50° off the earth's (steel beside a desk), constant in the room.
const Vec3 kStaticFieldNed(-20.0, 25.0, 23.0);

struct HandTurning {
  Vec3 bias_error = Vec3::Zero();
  FieldUpdateCounters counters;
};

// 60 s of a person standing and turning the sensor in the hand (about every axis, slowly),
// the field in the room turned about down by field_step_rad from field_step_s on. MARU, or with
// `gravity` AGU on the specific force.
HandTurning turnInTheHand(double baseline_s, double field_step_rad = 0.0, double field_step_s = 0.0,
                          bool gravity = false) {
  test::Random rng(11);
  const EstimatorParams params;
  GyroBiasEstimator bias(params);
  RotatedFieldUpdate maru(gravity ? RotatedFieldUpdateParams{baseline_s, params.agu_residual_accel_bias_m_s2, 0.005,
                                                             params.field_update_max_nis}
                                  : RotatedFieldUpdateParams{baseline_s, params.mag_residual_hard_iron_uT, 0.05,
                                                             params.field_update_max_nis});
  GyroFrame frame;
  Quat q_nb = Quat::Identity();
  for (int k = 0; k < 6000; ++k) {
    const double t = k * kDt;
    const Vec3 rate(0.4 * std::sin(0.7 * t), 0.3 * std::cos(0.45 * t), 0.5 * std::sin(0.3 * t + 1.0));
    q_nb = q_nb * gyroIncrement(rate, kDt);
    const Vec3 gyro = rate + kTrueBias + rng.gaussian(0.003);
    const Vec3 accel = q_nb.conjugate() * Vec3(0.0, 0.0, -9.81) + rng.gaussian(0.02);
    const Vec3 field_ned = Eigen::AngleAxisd(t >= field_step_s ? field_step_rad : 0.0, Vec3::UnitZ()) * kStaticFieldNed;
    const Vec3 field = q_nb.conjugate() * field_ned + rng.gaussian(kFieldNoiseUT);
    bias.update(gyro, accel, nullptr, kDt);
    frame.advance(gyroIncrement(gyro - bias.bias(), kDt));
    maru.advance(frame.frameFromSensor(), kDt);
    if (gravity) {
      maru.update(bias, accel, frame.frameFromSensor(), /*applies=*/true, 0.02);
    } else {
      maru.update(bias, field, frame.frameFromSensor(), /*applies=*/true, kFieldNoiseUT);
    }
  }
  return {bias.bias() - kTrueBias, maru.counters()};
}

TEST(RotatedFieldUpdate, AStaticFieldTeachesTheBiasAboutEveryAxis) {
  const HandTurning off = turnInTheHand(0.0);
  EXPECT_EQ(off.counters.applied, 0U);
  // Without MARU nothing measures the bias here (no rest, no tilt corrections fed).
  EXPECT_GT(off.bias_error.norm(), 0.01);
  const HandTurning on = turnInTheHand(2.0);
  EXPECT_GE(on.counters.applied, 25U);  // one per 2 s baseline
  EXPECT_EQ(on.counters.rejected_by_gate, 0U);
  EXPECT_LT(on.bias_error.cwiseAbs().maxCoeff(), 0.003) << on.bias_error.transpose();
}

TEST(RotatedFieldUpdate, AguOnGravityTeachesTheBiasAcrossTheVerticalsItSaw) {
  // The hand tilts the sensor by up to 30-50°, so the vertical has seen several sensor axes:
  // gravity's change observes the bias across each of them (AGU, eqs. 44-46).
  const HandTurning agu = turnInTheHand(2.0, 0.0, 0.0, /*gravity=*/true);
  EXPECT_GE(agu.counters.applied, 25U);
  EXPECT_LT(agu.bias_error.cwiseAbs().maxCoeff(), 0.003) << agu.bias_error.transpose();
}

TEST(RotatedFieldUpdate, ABaselineOverWhichTheFieldMovedIsRejected) {
  // A steel door swung open at 31 s turns the field in the room by 30° at once (20 µT at 40 µT):
  // the baseline across it is many sigmas off and changes nothing; the others still teach. (A
  // field that moves gradually is the detector's to catch: its direction test ends the period.)
  const HandTurning stepped = turnInTheHand(2.0, 30.0 * M_PI / 180.0, 31.0);
  EXPECT_EQ(stepped.counters.rejected_by_gate, 1U);
  EXPECT_GE(stepped.counters.applied, 25U);
  EXPECT_LT(stepped.bias_error.cwiseAbs().maxCoeff(), 0.003) << stepped.bias_error.transpose();
}

TEST(RotatedFieldUpdate, ABaselineDoesNotReachAcrossAPause) {
  const EstimatorParams params;
  GyroBiasEstimator bias(params);
  RotatedFieldUpdate maru({1.0, params.mag_residual_hard_iron_uT, 0.05, params.field_update_max_nis});
  GyroFrame frame;
  const Vec3 field(20.0, 5.0, 40.0);
  // 0.9 s in a period, one sample out of it, 0.9 s in again: no baseline of 1 s was whole.
  for (int k = 0; k < 190; ++k) {
    maru.advance(frame.frameFromSensor(), kDt);
    maru.update(bias, field, frame.frameFromSensor(), /*applies=*/k != 90, kFieldNoiseUT);
  }
  EXPECT_EQ(maru.counters().applied + maru.counters().rejected_by_gate, 0U);
  // ... then one more second is.
  for (int k = 0; k < 20; ++k) {
    maru.advance(frame.frameFromSensor(), kDt);
    maru.update(bias, field, frame.frameFromSensor(), true, kFieldNoiseUT);
  }
  EXPECT_EQ(maru.counters().applied, 1U);
}

}  // namespace
}  // namespace headingd::core
