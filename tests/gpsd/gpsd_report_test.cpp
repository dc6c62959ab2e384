// gpsd's JSON lines (as gpsd 3.22 sends them, https://gpsd.io/gpsd_json.html) into fixes.
#include <gtest/gtest.h>

#include "headingd/gpsd/gpsd_report.hpp"

namespace headingd::gpsd {
namespace {

// A TPV of gpsd 3.22 for the demo capture's RMC of 12:00:13 (config/demo/sim-urban-walk.nmea).
constexpr const char* kTpv =
    R"({"class":"TPV","device":"/dev/pts/0","mode":3,"time":"2026-06-01T12:00:13.000Z","ept":0.005,)"
    R"("lat":59.330039667,"lon":18.069976833,"altHAE":0.8000,"altMSL":0.8000,"alt":0.8000,"track":33.3600,)"
    R"("magtrack":41.0600,"magvar":7.7,"speed":1.295,"climb":-0.500,"geoidSep":0.000,"eph":19.000})";

TEST(GpsdReport, TpvGivesTimePositionCourseSpeedAndVariation) {
  const GpsdReport r = parseGpsdReport(kTpv);
  const auto* tpv = std::get_if<TpvReport>(&r);
  ASSERT_NE(tpv, nullptr);
  EXPECT_TRUE(tpv->missing.empty());
  const nmea::Fix& f = tpv->fix;
  ASSERT_TRUE(f.utc_ns && f.time_of_day_ns && f.position && f.mode && f.course_deg && f.speed_mps && f.magvar_deg);
  EXPECT_EQ(*f.utc_ns, 1'780'315'213'000'000'000);  // 2026-06-01T12:00:13Z
  EXPECT_EQ(*f.time_of_day_ns, (12 * 3600 + 13) * 1'000'000'000LL);
  EXPECT_EQ(*f.mode, nmea::FixMode::k3D);
  EXPECT_DOUBLE_EQ(f.position->lat_deg, 59.330039667);
  EXPECT_DOUBLE_EQ(f.position->lon_deg, 18.069976833);
  EXPECT_DOUBLE_EQ(*f.course_deg, 33.36);
  EXPECT_DOUBLE_EQ(*f.speed_mps, 1.295);
  EXPECT_DOUBLE_EQ(*f.magvar_deg, 7.7);
  EXPECT_DOUBLE_EQ(*f.alt_msl_m + *f.geoid_separation_m, 0.8);
}

TEST(GpsdReport, HeightFromAltHaeAloneIsKeptAsHeightAboveTheEllipsoid) {
  const auto r =
      parseGpsdReport(R"({"class":"TPV","mode":3,"lat":44.0,"lon":-121.0,"altHAE":1108.1,"geoidSep":-19.6})");
  const auto& f = std::get<TpvReport>(r).fix;
  EXPECT_NEAR(*f.alt_msl_m + *f.geoid_separation_m, 1108.1, 1e-9);
  EXPECT_NEAR(*f.alt_msl_m, 1127.7, 1e-9);
}

TEST(GpsdReport, NoFixTpvHasNoPositionAndNothingMissing) {
  const auto r = parseGpsdReport(R"({"class":"TPV","device":"/dev/pts/0","mode":1})");
  const auto& tpv = std::get<TpvReport>(r);
  EXPECT_TRUE(tpv.missing.empty());
  EXPECT_EQ(*tpv.fix.mode, nmea::FixMode::kNoFix);
  EXPECT_FALSE(tpv.fix.position);
  EXPECT_FALSE(tpv.fix.utc_ns);
}

TEST(GpsdReport, MissingModeOrPositionOfAFixIsNamed) {
  EXPECT_EQ(std::get<TpvReport>(parseGpsdReport(R"({"class":"TPV","lat":1.0,"lon":2.0})")).missing, "mode");
  const auto r = parseGpsdReport(R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:13.000Z","lat":1.0})");
  const auto& tpv = std::get<TpvReport>(r);
  EXPECT_EQ(tpv.missing, "lat/lon");
  EXPECT_FALSE(tpv.fix.position);
}

TEST(GpsdReport, SkyGivesTheDops) {
  const auto r = parseGpsdReport(R"({"class":"SKY","hdop":0.98,"pdop":1.64,"vdop":1.31,"uSat":10,"satellites":[]})");
  const auto& sky = std::get<SkyReport>(r);
  EXPECT_DOUBLE_EQ(*sky.hdop, 0.98);
  EXPECT_DOUBLE_EQ(*sky.pdop, 1.64);
  EXPECT_DOUBLE_EQ(*sky.vdop, 1.31);
  EXPECT_EQ(*sky.satellites_used, 10);
}

TEST(GpsdReport, OtherClassesAreNamed) {
  EXPECT_EQ(
      std::get<OtherReport>(parseGpsdReport(R"({"class":"VERSION","release":"3.22","proto_major":3})")).class_name,
      "VERSION");
}

TEST(GpsdReport, BadLinesAreMalformedWithAReason) {
  for (const char* line : {
           R"({"class":"TPV","mode":3,"lat":59.3)",                      // cut mid-way
           R"(not json at all)",                                         //
           R"([1,2,3])",                                                 // not an object
           R"({"mode":3})",                                              // no class
           R"({"class":"TPV","mode":"3"})",                              // a string for a number
           R"({"class":"TPV","mode":7})",                                // no such mode
           R"({"class":"TPV","mode":3,"lat":91.0,"lon":0.0})",           // beyond the pole
           R"({"class":"TPV","mode":3,"time":"yesterday"})",             // not ISO 8601
           R"({"class":"TPV","mode":3,"time":"2026-02-30T00:00:00Z"})",  // no such day
           R"({"class":"SKY","hdop":"low"})",
       }) {
    const auto r = parseGpsdReport(line);
    const auto* bad = std::get_if<MalformedReport>(&r);
    ASSERT_NE(bad, nullptr) << line;
    EXPECT_FALSE(bad->why.empty()) << line;
  }
}

TEST(GpsdReport, IsoTimesWithAndWithoutFractions) {
  EXPECT_EQ(parseIsoUtcNs("1970-01-01T00:00:00Z"), 0);
  EXPECT_EQ(parseIsoUtcNs("1970-01-01T00:00:01.250Z"), 1'250'000'000);
  EXPECT_EQ(parseIsoUtcNs("2000-03-01T00:00:00.000Z"), 951'868'800'000'000'000);
  EXPECT_FALSE(parseIsoUtcNs("2000-03-01T00:00:00.000"));  // no Z: not UTC
  EXPECT_FALSE(parseIsoUtcNs("2000-03-01T24:00:00.000Z"));
  EXPECT_FALSE(parseIsoUtcNs("6158-06-01T12:00:14Z"));  // beyond int64 nanoseconds (found by fuzzing)
  EXPECT_FALSE(parseIsoUtcNs("-999-06-01T12:00:14Z"));
  EXPECT_TRUE(parseIsoUtcNs("2200-12-31T23:59:59Z"));
  EXPECT_FALSE(parseIsoUtcNs("2000-03-01T00:00:00.000ZZ"));
}

}  // namespace
}  // namespace headingd::gpsd
