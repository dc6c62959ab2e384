// The configured place ([place], headingd-replay --place): the table's keys and their errors,
// the date the model is evaluated on, and the pipeline taking the model's field and
// declination there until a GPS fix gives the position.
#include "headingd/core/configured_place.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/core/config_error.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/toml_document.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::core {
namespace {

WorldMagneticModel wmm2025() {
  return WorldMagneticModel(
      parseWmmCoefficients(files::readMaybeGzipFile(HEADINGD_WMM_COF, files::kWmmFileLimit), HEADINGD_WMM_COF));
}

std::optional<ConfiguredPlace> parse(const std::string& text) {
  const toml::table doc = parseTomlDocument(text, "test.toml");
  return parsePlaceTable(doc["place"].as_table(), "test.toml");
}

std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ConfiguredPlace, TableKeys) {
  EXPECT_FALSE(parse("[estimator]\n").has_value());
  EXPECT_FALSE(parse("[place]\n").has_value());  // the shipped file's: no place
  const auto p = parse("[place]\nlatitude_deg = 59.35\nlongitude_deg = 18.07\nheight_m = 30\ndate = 2026-07-02\n");
  ASSERT_TRUE(p.has_value());
  EXPECT_DOUBLE_EQ(p->position.latitude_deg, 59.35);
  EXPECT_DOUBLE_EQ(p->position.longitude_deg, 18.07);
  EXPECT_DOUBLE_EQ(p->position.height_km, 0.03);
  ASSERT_TRUE(p->decimal_year.has_value());
  EXPECT_DOUBLE_EQ(*p->decimal_year, decimalYear(2026, 7, 2));
  const auto exact = parse("[place]\nlatitude_deg = -33.9\nlongitude_deg = 151.2\ndecimal_year = 2027.25\n");
  EXPECT_DOUBLE_EQ(exact->decimal_year.value(), 2027.25);
  EXPECT_DOUBLE_EQ(exact->position.height_km, 0.0);
  EXPECT_FALSE(parse("[place]\nlatitude_deg = 1\nlongitude_deg = 2\n")->decimal_year.has_value());
}

TEST(ConfiguredPlace, TableErrorsNameTheKey) {
  EXPECT_NE(errorOf("[place]\nlongitude_deg = 18\n").find("latitude_deg"), std::string::npos);
  EXPECT_NE(errorOf("[place]\nlatitude_deg = 91\nlongitude_deg = 18\n").find("latitude_deg"), std::string::npos);
  EXPECT_NE(errorOf("[place]\nlatitude_deg = 1\nlongitude_deg = 181\n").find("longitude_deg"), std::string::npos);
  EXPECT_NE(errorOf("[place]\nlatitude_deg = 1\nlongitude_deg = 2\ndate = \"2026-12-07\"\n").find("TOML date"),
            std::string::npos);
  EXPECT_NE(errorOf("[place]\nlatitude_deg = 1\nlongitude_deg = 2\ndate = 2026-02-30\n").find("date"),
            std::string::npos);
  EXPECT_NE(errorOf("[place]\nlatitude_deg = 1\nlongitude_deg = 2\ndate = 2026-12-07\ndecimal_year = 2026.9\n")
                .find("one of date or decimal_year"),
            std::string::npos);
  EXPECT_NE(errorOf("[place]\nlatitude_deg = 1\nlongitude_deg = 2\naltitude_m = 3\n").find("altitude_m"),
            std::string::npos);
}

TEST(ConfiguredPlace, DateWithinTheModel) {
  const WorldMagneticModel wmm = wmm2025();
  ConfiguredPlace place;
  std::string warning;
  // No date: today's, as it is within the model's validity.
  EXPECT_DOUBLE_EQ(placeDecimalYear(place, 2026.93, wmm, &warning), 2026.93);
  EXPECT_TRUE(warning.empty());
  // A system clock in 1970 (no real-time clock): the model's first day, with a warning.
  EXPECT_DOUBLE_EQ(placeDecimalYear(place, 1970.0, wmm, &warning), wmm.epochYear());
  EXPECT_NE(warning.find("system date (1970.00)"), std::string::npos) << warning;
  warning.clear();
  EXPECT_DOUBLE_EQ(placeDecimalYear(place, 2040.0, wmm, &warning), wmm.validUntilYear());
  EXPECT_FALSE(warning.empty());
  // A date the user gave is taken as given, and refused outside the model.
  place.decimal_year = 2027.5;
  EXPECT_DOUBLE_EQ(placeDecimalYear(place, 1970.0, wmm, nullptr), 2027.5);
  place.decimal_year = 2019.0;
  EXPECT_THROW(placeDecimalYear(place, 2026.93, wmm, nullptr), ConfigError);
}

TEST(ConfiguredPlace, DecimalYearOfUnixTime) {
  EXPECT_DOUBLE_EQ(decimalYearOfUnixNs(1'735'689'600'000'000'000), 2025.0);  // 2025-01-01T00:00:00Z
  // 2024-12-31T12:00Z: day 366 of a leap year, half gone.
  EXPECT_NEAR(decimalYearOfUnixNs(1'735'646'400'000'000'000), 2024.0 + 365.5 / 366.0, 1e-12);
  EXPECT_NEAR(decimalYearOfUnixNs(0), 1970.0, 1e-12);
}

TEST(ConfiguredPlace, PipelineTakesTheModelThereUntilAFix) {
  const WorldMagneticModel wmm = wmm2025();
  HeadingPipeline pipeline(EstimatorParams{}, &wmm);
  EXPECT_EQ(pipeline.output().declination_sources, kDeclNone);
  EXPECT_FALSE(pipeline.estimator().magDisturbance().hasReference());
  const GeodeticPosition stockholm{59.35, 18.07, 0.03};
  ASSERT_TRUE(pipeline.setPlace(stockholm, 2026.93));
  EXPECT_EQ(pipeline.output().declination_sources, kDeclWmm);
  EXPECT_NEAR(pipeline.output().declination_rad, wmm.field(stockholm, 2026.93).declination_deg * kRadPerDeg, 1e-12);
  EXPECT_TRUE(pipeline.estimator().magDisturbance().hasReference());

  // A fix elsewhere replaces it.
  GpsObservation fix;
  fix.t_ns = 1'000'000'000;
  fix.fix_ok = true;
  fix.position = GeodeticPosition{-33.9, 151.2, 0.0};
  fix.decimal_year = 2026.93;
  pipeline.processGps(fix);
  EXPECT_NEAR(pipeline.output().declination_rad, wmm.field(*fix.position, 2026.93).declination_deg * kRadPerDeg, 1e-12);

  // Without a model there is nothing to take.
  HeadingPipeline without(EstimatorParams{}, nullptr);
  EXPECT_FALSE(without.setPlace(stockholm, 2026.93));
  EXPECT_EQ(without.output().declination_sources, kDeclNone);
}

TEST(ConfiguredPlace, DescribedForTheLog) {
  const WorldMagneticModel wmm = wmm2025();
  const std::string line = describePlace({59.35, 18.07, 0.03}, 2026.93, wmm);
  EXPECT_NE(line.find("place 59.3500, 18.0700, 30 m on 2026.93: WMM"), std::string::npos) << line;
  EXPECT_NE(line.find("declination"), std::string::npos);
}

}  // namespace
}  // namespace headingd::core
