// GPS dates that parse but are not today (a receiver's default date, a week-number rollover)
// are not the dates the World Magnetic Model is evaluated on (core/gps_date_check.hpp), in the
// check alone and through HeadingPipeline::processGps, which every GPS source feeds.
#include "headingd/core/gps_date_check.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "headingd/core/angles.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::core {
namespace {

constexpr std::int64_t kDayNs = 86'400'000'000'000;
constexpr double kDay = 1.0 / 365.25;

WorldMagneticModel wmm2025() {
  return WorldMagneticModel(
      parseWmmCoefficients(files::readMaybeGzipFile(HEADINGD_WMM_COF, files::kWmmFileLimit), HEADINGD_WMM_COF));
}

TEST(GpsDateCheck, DatesOutsideTheModelsValidityAreNotBelieved) {
  const WorldMagneticModel wmm = wmm2025();
  GpsDateCheck check(wmm);
  bool believed = true;
  // A receiver's default before its first fix, nothing in use yet: no date at all.
  EXPECT_FALSE(check.dateFor(1980.01, 0, &believed));
  EXPECT_FALSE(believed);
  EXPECT_EQ(*check.dateFor(2026.41, kDayNs, &believed), 2026.41);
  EXPECT_TRUE(believed);
  // 1024 weeks back (2006.8): the date in use carried to the epoch's time instead.
  const auto date = check.dateFor(2006.80, 3 * kDayNs, &believed);
  EXPECT_FALSE(believed);
  ASSERT_TRUE(date);
  EXPECT_NEAR(*date, 2026.41 + 2 * kDay, 1e-9);
  EXPECT_EQ(check.notBelieved(), 2u);
}

TEST(GpsDateCheck, ADateFarFromTheOneInUseIsNotBelievedUntilEpochsKeepAgreeing) {
  const WorldMagneticModel wmm = wmm2025();
  GpsDateCheck check(wmm);
  check.seed(2026.41);  // the configured place's date
  bool believed = false;
  EXPECT_EQ(*check.dateFor(2026.41 + 20 * kDay, 0, &believed), 2026.41 + 20 * kDay);  // within 30 days
  EXPECT_TRUE(believed);
  // Two years ahead, within the model's validity: one of the two is wrong.
  for (int epoch = 1; epoch < GpsDateCheck::kEpochsToReplace; ++epoch) {
    const std::int64_t t = epoch * 1'000'000'000LL;
    EXPECT_NEAR(*check.dateFor(2028.5, t, &believed), 2026.41 + 20 * kDay, 1e-6) << epoch;
    EXPECT_FALSE(believed);
  }
  EXPECT_EQ(*check.dateFor(2028.5, 40'000'000'000LL, &believed), 2028.5);  // they kept agreeing
  EXPECT_TRUE(believed);
  EXPECT_EQ(check.notBelieved(), static_cast<std::uint64_t>(GpsDateCheck::kEpochsToReplace - 1));
}

TEST(GpsDateCheck, ThePipelineEvaluatesTheModelOnTheDateInUseAndSaysSo) {
  const WorldMagneticModel wmm = wmm2025();
  HeadingPipeline pipeline(EstimatorParams{}, &wmm);
  GpsObservation fix;
  fix.t_ns = 1'000'000'000;
  fix.fix_ok = true;
  fix.position = GeodeticPosition{59.35, 18.07, 0.03};
  fix.decimal_year = 2026.41;
  EXPECT_EQ(pipeline.processGps(fix), nullptr);
  const double declination_2026 = pipeline.output().declination_rad;
  EXPECT_NEAR(declination_2026, wmm.field(*fix.position, 2026.41).declination_deg * kRadPerDeg, 1e-12);

  // A system clock outside the model's validity (not set: 1970) seeds nothing.
  EXPECT_FALSE(pipeline.seedGpsDate(1970.0));
  EXPECT_TRUE(pipeline.seedGpsDate(2026.40));

  // The same place a second later, the receiver after a week-number rollover.
  fix.t_ns += 1'000'000'000;
  fix.decimal_year = 2006.80;
  const char* problem = pipeline.processGps(fix);
  ASSERT_NE(problem, nullptr);
  EXPECT_NE(std::strstr(problem, "date outside the World Magnetic Model's validity"), nullptr) << problem;
  EXPECT_EQ(pipeline.gpsDatesNotBelieved(), 1u);
  EXPECT_EQ(pipeline.gpsValuesIgnored(), 1u);
  EXPECT_NEAR(pipeline.output().declination_rad, declination_2026, 1e-6);
  // Evaluated on 2006.8 it would have moved by more than a degree here.
  EXPECT_GT(std::abs(wmm.field(*fix.position, 2006.80).declination_deg * kRadPerDeg - declination_2026),
            1.0 * kRadPerDeg);
}

}  // namespace
}  // namespace headingd::core
