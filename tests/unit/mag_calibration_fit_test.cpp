// MagCalibrationFit and CalibratedImuStream: a magnetometer calibration is used while it
// explains the readings and set aside while the raw readings fit better.
#include "headingd/core/mag_calibration_fit.hpp"
#include "headingd/core/calibrated_imu_stream.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "test_support.hpp"

namespace headingd::core {
namespace {

using test::Random;

const Vec3 kFieldNed(15.0, 1.0, 50.0);  // µT, |m| 52.2
constexpr double kDt = 0.01;

// A hard-iron offset and soft iron of a magnet on the board: y = D m + o.
ImuCalibration magnetCalibration() {
  ImuCalibration c;
  c.mag.D << 1.3, 0.1, 0.0, 0.05, 0.8, 0.1, 0.0, -0.1, 1.1;
  c.mag.offset_uT = Vec3(40.0, 30.0, -20.0);
  c.mag.field_norm_uT = kFieldNed.norm();
  return c;
}

// The field in sensor axes at time t while the sensor tumbles about a fixed axis.
Vec3 fieldInSensor(double t, double rate_rad_s) {
  const Quat q_nb(Eigen::AngleAxisd(rate_rad_s * t, Vec3(0.3, -0.5, 0.8).normalized()));
  return q_nb.inverse() * kFieldNed;
}

ImuSample sampleAt(int i, const Vec3& mag_uT) {
  ImuSample s;
  s.t_ns = 1'000'000'000LL + static_cast<std::int64_t>(i) * 10'000'000LL;
  s.gyro_rad_s = Vec3::Zero();
  s.accel_m_s2 = Vec3(0.0, 0.0, -9.81);
  s.mag_uT = mag_uT;
  return s;
}

// Runs `seconds` of readings through the stream; distorted = the magnet is on the board.
void runReadings(CalibratedImuStream& stream, const ImuCalibration& c, int& i, double seconds, bool distorted,
                 double rate_rad_s, Random& rng) {
  for (const int end = i + static_cast<int>(seconds / kDt); i < end; ++i) {
    const Vec3 m = fieldInSensor(i * kDt, rate_rad_s);
    const Vec3 y = (distorted ? Vec3(c.mag.D * m + c.mag.offset_uT) : m) + rng.gaussian(0.5);
    stream.apply(sampleAt(i, y));
  }
}

// A stream on the magnet's calibration (magnetCalibration), its readings' noise drawn from
// `seed`; each run goes on from sample i, where the last one stopped.
struct MagnetStream {
  explicit MagnetStream(std::uint32_t seed) : rng(seed) {}
  void run(double seconds, bool distorted, double rate_rad_s) {
    runReadings(stream, c, i, seconds, distorted, rate_rad_s, rng);
  }
  const MagCalibrationFit& fit() const { return stream.magFit(); }

  const ImuCalibration c = magnetCalibration();
  CalibratedImuStream stream{c};
  Random rng;
  int i = 0;
};

TEST(MagCalibrationFit, AFittingCalibrationIsKeptThroughTurnsAndRest) {
  MagnetStream magnet(1);
  magnet.run(20.0, true, 1.0);
  EXPECT_LT(magnet.fit().calibratedFluctuation(), 0.02);
  EXPECT_GT(magnet.fit().rawFluctuation(), 0.1);
  magnet.run(20.0, true, 0.0);
  EXPECT_TRUE(magnet.fit().calibrationInUse());
  EXPECT_EQ(magnet.fit().setAside(), 0u);
}

TEST(MagCalibrationFit, IsSetAsideWhenTheMagnetIsGoneAndTakenBackWhenItReturns) {
  MagnetStream magnet(2);
  magnet.run(10.0, true, 1.0);
  magnet.run(10.0, false, 1.0);  // magnet taken off while turning
  EXPECT_FALSE(magnet.fit().calibrationInUse());
  EXPECT_EQ(magnet.fit().setAside(), 1u);
  // While set aside the estimator gets the raw reading.
  const ImuSample raw = sampleAt(magnet.i, fieldInSensor(magnet.i * kDt, 1.0));
  EXPECT_EQ(magnet.stream.apply(raw).mag_uT, raw.mag_uT);
  ++magnet.i;
  magnet.run(10.0, true, 1.0);  // and put back
  EXPECT_TRUE(magnet.fit().calibrationInUse());
  EXPECT_EQ(magnet.fit().takenBack(), 1u);
}

TEST(MagCalibrationFit, AtRestTheStatedStrengthDecides) {
  MagnetStream magnet(3);
  magnet.run(5.0, false, 0.0);  // still, no magnet: calibrated |m| is far from 52 µT
  EXPECT_FALSE(magnet.fit().calibrationInUse());
  // Without a stated strength a still sensor gives no evidence either way.
  ImuCalibration unstated = magnet.c;
  unstated.mag.field_norm_uT = 0.0;
  CalibratedImuStream quiet(unstated);
  int i = 0;
  runReadings(quiet, unstated, i, 5.0, false, 0.0, magnet.rng);
  EXPECT_TRUE(quiet.magFit().calibrationInUse());
}

TEST(MagCalibrationFit, AFieldThatDisturbsBothAlikeChangesNothing) {
  // A near-identity calibration and a nearby piece of steel whose field comes and goes.
  ImuCalibration c;
  c.mag.D = Mat3::Identity() * 1.02;
  c.mag.offset_uT = Vec3(1.0, -0.5, 0.3);
  c.mag.field_norm_uT = kFieldNed.norm();
  CalibratedImuStream stream(c);
  Random rng(4);
  for (int i = 0; i < 3000; ++i) {
    const double t = i * kDt;
    const Vec3 steel = Vec3(20.0, -10.0, 15.0) * std::max(0.0, std::sin(0.7 * t));
    stream.apply(sampleAt(i, c.mag.D * (fieldInSensor(t, 0.8) + steel) + c.mag.offset_uT + rng.gaussian(0.5)));
  }
  EXPECT_TRUE(stream.magFit().calibrationInUse());
  EXPECT_EQ(stream.magFit().setAside(), 0u);
}

TEST(MagCalibrationFit, NonFiniteReadingsAndTimeGoingBackDoNotSwitch) {
  MagnetStream magnet(5);
  magnet.run(5.0, true, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  magnet.stream.apply(sampleAt(magnet.i, Vec3(nan, 1.0, 2.0)));
  magnet.stream.apply(
      sampleAt(magnet.i - 100, magnet.c.mag.D * fieldInSensor(magnet.i * kDt, 1.0) + magnet.c.mag.offset_uT));
  magnet.run(5.0, true, 1.0);
  EXPECT_TRUE(magnet.fit().calibrationInUse());
  EXPECT_TRUE(std::isfinite(magnet.fit().calibratedFluctuation()));
}

TEST(MagCalibrationFit, WithoutACalibrationSamplesPassUnchanged) {
  CalibratedImuStream stream;
  const ImuSample s = sampleAt(0, Vec3(1.0, 2.0, 3.0));
  const ImuSample out = stream.apply(s);
  EXPECT_EQ(out.mag_uT, s.mag_uT);
  EXPECT_EQ(out.gyro_rad_s, s.gyro_rad_s);
}

}  // namespace
}  // namespace headingd::core
