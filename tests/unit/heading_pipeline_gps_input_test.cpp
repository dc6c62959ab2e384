// HeadingPipeline::processGps checks what it is given: an epoch with a value no receiver sends
// (a NaN variation, a latitude beyond ±90°) is rejected whole and counted, never thrown on and
// never let into the declination or the true heading.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::core {
namespace {

constexpr double kRad = std::numbers::pi / 180.0;

GpsObservation goodEpoch(std::int64_t t_ns) {
  GpsObservation g;
  g.t_ns = t_ns;
  g.fix_ok = true;
  g.position = GeodeticPosition{48.1, 11.5, 0.5};
  g.decimal_year = 2026.4;
  g.speed_mps = 0.0;
  g.hdop = 0.9;
  g.magvar_rad = 4.0 * kRad;
  return g;
}

TEST(HeadingPipelineGpsInput, ImpossibleEpochsAreRejectedAndCountedNotThrownOrFused) {
  const WorldMagneticModel wmm(
      parseWmmCoefficients(files::readWholeFile(HEADINGD_WMM_COF, files::kWmmFileLimit), HEADINGD_WMM_COF));
  HeadingPipeline pipeline(EstimatorParams{}, &wmm);
  ImuSample s;
  s.accel_m_s2 = Vec3(0.0, 0.0, -9.81);
  s.mag_uT = Vec3(20.0, 0.0, 40.0);
  for (int i = 0; i < 200; ++i) {
    s.t_ns = i * 10'000'000LL;
    pipeline.process(s);
  }
  ASSERT_TRUE(pipeline.processGps(goodEpoch(2'000'000'000)));
  const double declination = pipeline.output().declination_rad;
  ASSERT_TRUE(std::isfinite(declination));

  GpsObservation nan_variation = goodEpoch(2'100'000'000);
  nan_variation.magvar_rad = std::nan("");
  EXPECT_FALSE(pipeline.processGps(nan_variation));
  GpsObservation variation_200 = goodEpoch(2'200'000'000);
  variation_200.magvar_rad = 200.0 * kRad;
  EXPECT_FALSE(pipeline.processGps(variation_200));
  GpsObservation north_of_the_pole = goodEpoch(2'300'000'000);
  north_of_the_pole.position->latitude_deg = 95.0;  // the WMM throws on it
  EXPECT_FALSE(pipeline.processGps(north_of_the_pole));
  GpsObservation negative_speed = goodEpoch(2'400'000'000);
  negative_speed.speed_mps = -1.0;
  EXPECT_FALSE(pipeline.processGps(negative_speed));
  EXPECT_STREQ(gpsObservationProblem(north_of_the_pole), "latitude outside [-90, 90] degrees");

  EXPECT_EQ(pipeline.gpsEpochsRejected(), 4u);
  EXPECT_EQ(pipeline.output().declination_rad, declination);
  EXPECT_TRUE(std::isfinite(pipeline.output().heading_true_rad));
  EXPECT_TRUE(pipeline.processGps(goodEpoch(2'500'000'000)));
  EXPECT_EQ(pipeline.gpsEpochsRejected(), 4u);
}

}  // namespace
}  // namespace headingd::core
