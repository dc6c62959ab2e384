// HeadingPipeline::processGps with values it cannot use: each is left out and counted, the
// outputs stay finite, and nothing throws (the reproducers of the fuzz target tests/fuzz/
// pipeline_fuzz.cpp, made small).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::core {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

WorldMagneticModel wmm2025() {
  return WorldMagneticModel(
      parseWmmCoefficients(files::readMaybeGzipFile(HEADINGD_WMM_COF, files::kWmmFileLimit), HEADINGD_WMM_COF));
}

// A second of a level, still IMU at 100 Hz in a field pointing north and down.
void feedStill(HeadingPipeline& pipeline, std::int64_t& t_ns) {
  for (int i = 0; i < 100; ++i) {
    ImuSample s;
    s.t_ns = t_ns += 10'000'000;
    s.accel_m_s2 = Vec3(0.0, 0.0, 9.81);
    s.mag_uT = Vec3(20.0, 0.0, 43.0);
    pipeline.process(s);
  }
}

// A pipeline after a second of still samples, and the time of the last one.
struct StillPipeline {
  explicit StillPipeline(const WorldMagneticModel* wmm) : pipeline(EstimatorParams{}, wmm) { feedStill(pipeline, t); }
  HeadingPipeline pipeline;
  std::int64_t t = 0;
};

GpsObservation fixAt(std::int64_t t_ns) {
  GpsObservation g;
  g.t_ns = t_ns;
  g.fix_ok = true;
  g.position = GeodeticPosition{48.1, 11.6, 0.5};
  g.decimal_year = 2026.9;
  g.course_rad = 1.0;
  g.speed_mps = 1.4;
  g.hdop = 0.9;
  return g;
}

void expectFiniteOutput(const HeadingPipeline& p) {
  EXPECT_TRUE(std::isfinite(p.output().heading_true_rad));
  EXPECT_TRUE(std::isfinite(p.output().declination_rad));
  EXPECT_TRUE(p.output().attitude.q_nb.coeffs().allFinite());
}

TEST(HeadingPipelineGps, NanMagneticVariationIsLeftOutAndCounted) {
  StillPipeline still(nullptr);
  auto& [pipeline, t] = still;
  GpsObservation g = fixAt(t);
  g.magvar_rad = kNaN;
  pipeline.processGps(g);
  expectFiniteOutput(pipeline);
  EXPECT_EQ(pipeline.output().declination_sources, kDeclNone);
  EXPECT_EQ(pipeline.gpsValuesIgnored(), 1u);
}

TEST(HeadingPipelineGps, VariationBeyond180DegreesIsLeftOut) {
  StillPipeline still(nullptr);
  auto& [pipeline, t] = still;
  GpsObservation g = fixAt(t);
  g.magvar_rad = 200.0 * kRadPerDeg;
  pipeline.processGps(g);
  EXPECT_EQ(pipeline.output().declination_sources, kDeclNone);
  EXPECT_EQ(pipeline.gpsValuesIgnored(), 1u);
  g.magvar_rad = 0.1;  // a plausible one is used
  pipeline.processGps(g);
  EXPECT_EQ(pipeline.output().declination_sources, kDeclReceiver);
  EXPECT_DOUBLE_EQ(pipeline.output().declination_rad, 0.1);
}

TEST(HeadingPipelineGps, ImpossiblePositionIsNoFixAndDoesNotThrow) {
  const WorldMagneticModel wmm = wmm2025();
  StillPipeline still(&wmm);
  auto& [pipeline, t] = still;
  GpsObservation g = fixAt(t);
  g.position->latitude_deg = 200.0;
  EXPECT_NO_THROW(pipeline.processGps(g));
  EXPECT_EQ(pipeline.output().declination_sources, kDeclNone);  // no WMM declination from it
  g.position->latitude_deg = 48.1;
  g.position->longitude_deg = std::numeric_limits<double>::infinity();
  EXPECT_NO_THROW(pipeline.processGps(g));
  EXPECT_EQ(pipeline.gpsValuesIgnored(), 2u);
  g.position->longitude_deg = 11.6;
  pipeline.processGps(g);
  EXPECT_EQ(pipeline.output().declination_sources, kDeclWmm);
  expectFiniteOutput(pipeline);
}

TEST(HeadingPipelineGps, DateWhereTheModelOverflowsIsLeftOut) {
  const WorldMagneticModel wmm = wmm2025();
  StillPipeline still(&wmm);
  auto& [pipeline, t] = still;
  GpsObservation g = fixAt(t);
  g.decimal_year = std::numeric_limits<double>::max();  // finite, but the secular change overflows
  pipeline.processGps(g);
  EXPECT_EQ(pipeline.output().declination_sources, kDeclNone);
  EXPECT_EQ(pipeline.gpsValuesIgnored(), 1u);
  expectFiniteOutput(pipeline);
}

TEST(HeadingPipelineGps, NegativeSpeedAndHdopAreLeftOut) {
  StillPipeline still(nullptr);
  auto& [pipeline, t] = still;
  GpsObservation g = fixAt(t);
  g.speed_mps = -3.0;
  g.hdop = -1.0;
  g.course_rad = kNaN;
  pipeline.processGps(g);
  EXPECT_EQ(pipeline.gpsValuesIgnored(), 3u);
  expectFiniteOutput(pipeline);
}

// Corrupt stamps anywhere in the int64 range: the intervals between them saturate instead of
// overflowing (the sanitizer build, tools/scripts/sanitize.sh, checks there is no overflow).
TEST(HeadingPipelineGps, StampsAtTheEndsOfTheRangeDoNotOverflow) {
  StillPipeline still(nullptr);
  auto& [pipeline, t] = still;
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  pipeline.processGps(fixAt(kMax));
  pipeline.processGps(fixAt(kMin));  // interval since kMax; walking since kMin
  feedStill(pipeline, t);            // each sample: time since the walking epoch at kMin
  pipeline.processGps(fixAt(kMax));  // interval since kMin
  expectFiniteOutput(pipeline);
  EXPECT_EQ(pipeline.gpsValuesIgnored(), 0u);
}

}  // namespace
}  // namespace headingd::core
