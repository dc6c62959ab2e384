#include <gtest/gtest.h>

#include "headingd/nmea/sentences.hpp"
#include "nmea_test_support.hpp"

namespace headingd::nmea {
namespace {

using test::decodeAs;
using test::decodeOk;
using test::sentence;

constexpr std::int64_t kS = 1'000'000'000;

DecodeStatus statusOf(std::string_view body) { return decodeSentence(sentence(body)).status; }

TEST(Sentences, Gga) {
  const auto d = decodeOk("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
  EXPECT_EQ(d.talker, Talker::kGP);
  EXPECT_EQ(d.type, SentenceType::kGGA);
  EXPECT_EQ(d.invalid_fields, 0);
  const auto& g = std::get<Gga>(d.data);
  EXPECT_EQ(*g.time_of_day_ns, (12 * 3600 + 35 * 60 + 19) * kS);
  EXPECT_NEAR(g.position->lat_deg, 48.1173, 1e-9);
  EXPECT_NEAR(g.position->lon_deg, 11.516666667, 1e-9);
  EXPECT_EQ(*g.quality, 1);
  EXPECT_EQ(*g.satellites_used, 8);
  EXPECT_DOUBLE_EQ(*g.hdop, 0.9);
  EXPECT_DOUBLE_EQ(*g.alt_msl_m, 545.4);
  EXPECT_DOUBLE_EQ(*g.geoid_separation_m, 46.9);
  EXPECT_FALSE(g.dgps_age_s);
  EXPECT_FALSE(g.dgps_station);
}

TEST(Sentences, GgaWithDgpsFields) {
  const auto g =
      decodeAs<Gga>("GPGGA,132820.60,4134.49821229,N,09345.03351845,W,2,09,1.0,278.020,M,-31.442,M,7.6,0133");
  EXPECT_NEAR(g.position->lon_deg, -93.750558641, 1e-9);
  EXPECT_DOUBLE_EQ(*g.dgps_age_s, 7.6);
  EXPECT_EQ(*g.dgps_station, 133);
  EXPECT_DOUBLE_EQ(*g.geoid_separation_m, -31.442);
}

TEST(Sentences, GgaWithoutFix) {
  // Quectel and Hemisphere before a fix (hemi.log).
  const auto g = decodeAs<Gga>("GPGGA,,,,,,0,,,,M,,M,,");
  EXPECT_FALSE(g.time_of_day_ns);
  EXPECT_FALSE(g.position);
  EXPECT_EQ(*g.quality, 0);
  EXPECT_FALSE(g.alt_msl_m);
}

TEST(Sentences, GgaCorruptFieldsAreCountedNotUsed) {
  const auto d = decodeOk("GPGGA,123519,4807.038,N,01131.000,X,1,08,0.9,545.4,F,46.9,M,,");
  const auto& g = std::get<Gga>(d.data);
  EXPECT_FALSE(g.position);   // 'X' is no hemisphere
  EXPECT_FALSE(g.alt_msl_m);  // feet are not what GGA sends
  EXPECT_EQ(d.invalid_fields, 2);
}

TEST(Sentences, GgaWithWrongFieldCountIsMalformed) {
  // gp-320fw-2019-04-07-coldboot.log: two sentences run together, checksum still right.
  EXPECT_EQ(statusOf("GPGGA,000428.00,00,3,1,12,23,86,270,,13,70,270,40,24,59,270,,04,41,270,40"),
            DecodeStatus::kMalformed);
  EXPECT_EQ(statusOf("GPGGA,123519,4807.038,N,01131.000,E,1,08"), DecodeStatus::kMalformed);
}

TEST(Sentences, Rmc) {
  const auto d = decodeOk("GPRMC,225446.33,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E,A");
  const auto& r = std::get<Rmc>(d.data);
  EXPECT_EQ(*r.time_of_day_ns, (22 * 3600 + 54 * 60 + 46) * kS + 330'000'000);
  EXPECT_EQ(r.status, 'A');
  EXPECT_NEAR(r.position->lat_deg, 49.274166667, 1e-9);
  EXPECT_NEAR(r.position->lon_deg, -123.185333333, 1e-9);
  EXPECT_DOUBLE_EQ(*r.speed_mps, 0.5 * 1852.0 / 3600.0);
  EXPECT_DOUBLE_EQ(*r.course_deg, 54.7);
  EXPECT_EQ(r.date->day, 19);
  EXPECT_EQ(r.date->month, 11);
  EXPECT_EQ(r.date->yy, 94);
  EXPECT_DOUBLE_EQ(*r.magvar_deg, 20.3);
  EXPECT_EQ(*r.mode_indicator, 'A');
  EXPECT_FALSE(r.nav_status);
  EXPECT_EQ(d.invalid_fields, 0);
}

TEST(Sentences, RmcWestVariationIsNegative) {
  const auto r = decodeAs<Rmc>("GPRMC,125106,V,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W,S");
  EXPECT_EQ(r.status, 'V');
  EXPECT_DOUBLE_EQ(*r.magvar_deg, -10.5);
  EXPECT_EQ(*r.mode_indicator, 'S');
}

TEST(Sentences, RmcVariationBeyond180DegreesIsNotUsedAndCounted) {
  // A variation is 0..180 degrees east or west; 200 would put the declination 20 degrees off.
  const auto d = decodeOk("GPRMC,125106,A,3854.5087,N,07726.4523,W,0.0,0.0,241011,200.0,E,A");
  EXPECT_FALSE(std::get<Rmc>(d.data).magvar_deg);
  EXPECT_EQ(d.invalid_fields, 1);
  EXPECT_DOUBLE_EQ(*decodeAs<Rmc>("GPRMC,125106,A,3854.5087,N,07726.4523,W,0.0,0.0,241011,180.0,W,A").magvar_deg,
                   -180.0);
}

TEST(Sentences, RmcVersionsByFieldCount) {
  // NMEA 2.0 (no mode indicator), 2.3 (mode), 4.1 (mode + navigation status).
  EXPECT_FALSE(decodeAs<Rmc>("GPRMC,005947.00,A,3715.6616,N,12157.6709,W,0.0,0.0,080710,,").mode_indicator);
  const auto r41 = decodeAs<Rmc>("GNRMC,001053.00,A,4404.14083,N,12118.85886,W,0.043,,180817,,,A,V");
  EXPECT_EQ(*r41.mode_indicator, 'A');
  EXPECT_EQ(*r41.nav_status, 'V');
  EXPECT_FALSE(r41.course_deg);
  EXPECT_EQ(statusOf("GPRMC,000346.03,A,4808"), DecodeStatus::kMalformed);
}

TEST(Sentences, Vtg) {
  const auto v = decodeAs<Vtg>("GPVTG,054.7,T,034.4,M,005.5,N,010.2,K,A");
  EXPECT_DOUBLE_EQ(*v.course_deg, 54.7);
  EXPECT_DOUBLE_EQ(*v.course_magnetic_deg, 34.4);
  EXPECT_DOUBLE_EQ(*v.speed_mps, 5.5 * kKnotToMps);
  EXPECT_EQ(*v.mode_indicator, 'A');
}

TEST(Sentences, VtgFallsBackToKmh) {
  const auto v = decodeAs<Vtg>("GPVTG,054.7,T,,M,,N,36.0,K");
  EXPECT_DOUBLE_EQ(*v.speed_mps, 10.0);
  EXPECT_FALSE(v.course_magnetic_deg);
  EXPECT_FALSE(v.mode_indicator);
}

TEST(Sentences, Gns) {
  const auto g = decodeAs<Gns>("GPGNS,224749.00,3333.4268304,N,11153.3538273,W,DA,19,0.6,406.110,-26.294,6.0,0138,S");
  EXPECT_EQ(*g.time_of_day_ns, (22 * 3600 + 47 * 60 + 49) * kS);
  EXPECT_NEAR(g.position->lat_deg, 33.557113840, 1e-9);
  EXPECT_EQ(g.mode_indicators[0], 'D');
  EXPECT_EQ(g.mode_indicators[1], 'A');
  EXPECT_EQ(g.mode_indicators[2], '\0');
  EXPECT_EQ(*g.satellites_used, 19);
  EXPECT_DOUBLE_EQ(*g.alt_msl_m, 406.110);
  EXPECT_DOUBLE_EQ(*g.geoid_separation_m, -26.294);
  EXPECT_EQ(*g.dgps_station, 138);
  EXPECT_EQ(*g.nav_status, 'S');
  // Before NMEA 4.1 there is no navigation status.
  EXPECT_FALSE(decodeAs<Gns>("GNGNS,053229.438,,,,,NNNN,00,,,0.0,,0000").nav_status);
}

TEST(Sentences, Gsa) {
  const auto g = decodeAs<Gsa>("GPGSA,A,3,03,07,08,11,13,16,19,23,24,28,,,3.6,2.0,3.0");
  EXPECT_EQ(*g.selection, 'A');
  EXPECT_EQ(*g.fix_mode, 3);
  EXPECT_EQ(g.satellites_listed, 10);
  EXPECT_DOUBLE_EQ(*g.pdop, 3.6);
  EXPECT_DOUBLE_EQ(*g.hdop, 2.0);
  EXPECT_DOUBLE_EQ(*g.vdop, 3.0);
  EXPECT_FALSE(g.system_id);
  // NMEA 4.1 adds the GNSS system ID.
  EXPECT_EQ(*decodeAs<Gsa>("GNGSA,A,3,82,66,81,,,,,,,,,,1.05,0.64,0.83,2").system_id, 2);
  // The Navior-24 lists 24 PRNs.
  const auto n24 = decodeAs<Gsa>("GPGSA,A,3,27,23,13,07,25,,,,,,,,,,,,,,,,,,,,07.9,06.0,05.2");
  EXPECT_EQ(n24.satellites_listed, 5);
  EXPECT_DOUBLE_EQ(*n24.vdop, 5.2);
  // i.Trek M3: "$GPGSA,A,1,,,,*32" has the wrong number of fields.
  EXPECT_EQ(decodeSentence("$GPGSA,A,1,,,,*32").status, DecodeStatus::kMalformed);
}

TEST(Sentences, Gst) {
  const auto g = decodeAs<Gst>("GPGST,172814.0,0.006,0.023,0.020,273.6,0.023,0.020,0.031");
  EXPECT_EQ(*g.time_of_day_ns, (17 * 3600 + 28 * 60 + 14) * kS);
  EXPECT_DOUBLE_EQ(*g.rms_m, 0.006);
  EXPECT_DOUBLE_EQ(*g.orientation_deg, 273.6);
  EXPECT_DOUBLE_EQ(*g.lat_sigma_m, 0.023);
  EXPECT_DOUBLE_EQ(*g.lon_sigma_m, 0.020);
  EXPECT_DOUBLE_EQ(*g.alt_sigma_m, 0.031);
}

TEST(Sentences, Hdt) {
  EXPECT_DOUBLE_EQ(*decodeAs<Hdt>("GPHDT,341.8,T").heading_deg, 341.8);
  EXPECT_FALSE(decodeAs<Hdt>("GPHDT,,T").heading_deg);  // hemi.log before a fix
  EXPECT_FALSE(decodeAs<Hdt>("GPHDT,341.8,M").heading_deg);
  // A gyro compass talks as HE: not a GNSS talker, so not ours.
  EXPECT_EQ(statusOf("HEHDT,341.8,T"), DecodeStatus::kUnsupportedTalker);
}

TEST(Sentences, Zda) {
  const auto z = decodeAs<Zda>("GPZDA,160012.71,11,03,2004,-1,00");
  EXPECT_EQ(*z.time_of_day_ns, (16 * 3600 + 12) * kS + 710'000'000);
  EXPECT_EQ(*z.day, 11);
  EXPECT_EQ(*z.month, 3);
  EXPECT_EQ(*z.year, 2004);
  EXPECT_EQ(*z.zone_hours, -1);
  EXPECT_EQ(*z.zone_minutes, 0);
  // u-blox before a fix sends empty fields.
  const auto empty = decodeAs<Zda>("GPZDA,,,,,00,00");
  EXPECT_FALSE(empty.time_of_day_ns);
  EXPECT_FALSE(empty.year);
}

// A zone of 1e50 hours overflowed the int conversion (found by fuzzing): beyond -14..+14 the
// zone is a bad field, counted, and the time and date are kept.
TEST(Sentences, ZdaZoneBeyondFourteenHoursIsNotUsedAndCounted) {
  const auto d = decodeOk("GPZDA,160012.71,11,03,2004,7.77778e+50,00");
  const auto& z = std::get<Zda>(d.data);
  EXPECT_FALSE(z.zone_hours);
  EXPECT_EQ(*z.year, 2004);
  EXPECT_EQ(d.invalid_fields, 1);
  EXPECT_EQ(*std::get<Zda>(decodeOk("GPZDA,160012.71,11,03,2004,+14,00").data).zone_hours, 14);
}

TEST(Sentences, Gll) {
  const auto g = decodeAs<Gll>("GPGLL,4916.45,N,12311.12,W,225444,A,A");
  EXPECT_NEAR(g.position->lat_deg, 49.274166667, 1e-9);
  EXPECT_EQ(*g.time_of_day_ns, (22 * 3600 + 54 * 60 + 44) * kS);
  EXPECT_EQ(g.status, 'A');
  EXPECT_EQ(*g.mode_indicator, 'A');
  EXPECT_FALSE(decodeAs<Gll>("GPGLL,3728.0549,N,12213.8639,W,014413.076,V").mode_indicator);
}

TEST(Sentences, EveryGnssTalker) {
  for (const char* t : {"GP", "GN", "GL", "GA", "GB", "GQ", "BD"}) {
    const auto d = decodeOk(std::string(t) + "GGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
    EXPECT_STREQ(talkerName(d.talker), t);
  }
}

TEST(Sentences, OthersAreClassifiedNotDecoded) {
  EXPECT_EQ(statusOf("GPGSV,3,1,10,03,41,050,46,07,60,317,49,08,34,315,45,11,35,148,45"),
            DecodeStatus::kUnsupportedType);
  EXPECT_EQ(statusOf("GPTXT,01,01,02,ANTSTATUS=OK"), DecodeStatus::kUnsupportedType);
  EXPECT_EQ(statusOf("PGRME,15.0,M,45.0,M,25.0,M"), DecodeStatus::kUnsupportedTalker);
  EXPECT_EQ(statusOf("PSTI,030,,,,"), DecodeStatus::kUnsupportedTalker);
  EXPECT_EQ(statusOf("IIHDT,341.8,T"), DecodeStatus::kUnsupportedTalker);
  EXPECT_EQ(statusOf("GPGGAX,1"), DecodeStatus::kUnsupportedTalker);
  EXPECT_EQ(decodeSentence(sentence("AIVDM,1,1,,A,13HOI:0P0000VOHLCnHQKwvL05Ip,0,0", '!')).status,
            DecodeStatus::kUnsupportedTalker);
}

TEST(Sentences, TooManyFieldsIsMalformed) {
  std::string body = "GPGSV";
  for (int i = 0; i < 80; ++i) body += ",";
  EXPECT_EQ(statusOf(body), DecodeStatus::kMalformed);
}

}  // namespace
}  // namespace headingd::nmea
