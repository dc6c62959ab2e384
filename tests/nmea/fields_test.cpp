#include <gtest/gtest.h>

#include "headingd/nmea/fields.hpp"

namespace headingd::nmea {
namespace {

TEST(Fields, DecimalAcceptsOnlyPlainNumbers) {
  EXPECT_DOUBLE_EQ(*parseDecimal("12.5"), 12.5);
  EXPECT_DOUBLE_EQ(*parseDecimal("-33.9"), -33.9);
  EXPECT_DOUBLE_EQ(*parseDecimal("+1.0"), 1.0);
  EXPECT_DOUBLE_EQ(*parseDecimal(".5"), 0.5);
  EXPECT_DOUBLE_EQ(*parseDecimal("5."), 5.0);
  EXPECT_DOUBLE_EQ(*parseDecimal("00176"), 176.0);
  for (const char* bad : {"", "-", ".", "1e3", "nan", "inf", "1.2.3", " 1", "1 ", "0x10", "M", "--1"}) {
    EXPECT_FALSE(parseDecimal(bad)) << bad;
  }
}

TEST(Fields, Integer) {
  EXPECT_EQ(*parseInteger("08"), 8);
  EXPECT_EQ(*parseInteger("0133"), 133);
  EXPECT_FALSE(parseInteger(""));
  EXPECT_FALSE(parseInteger("-1"));
  EXPECT_FALSE(parseInteger("1.0"));
  EXPECT_FALSE(parseInteger("9999999999"));  // would overflow int
}

TEST(Fields, TimeOfDay) {
  constexpr std::int64_t kS = 1'000'000'000;
  EXPECT_EQ(*parseTimeOfDay("123519"), (12 * 3600 + 35 * 60 + 19) * kS);
  EXPECT_EQ(*parseTimeOfDay("123519.25"), (12 * 3600 + 35 * 60 + 19) * kS + 250'000'000);
  EXPECT_EQ(*parseTimeOfDay("000000.001"), 1'000'000);
  EXPECT_EQ(*parseTimeOfDay("000000.123456789"), 123'456'789);
  EXPECT_EQ(*parseTimeOfDay("235960"), (23 * 3600 + 59 * 60 + 60) * kS);  // leap second
  for (const char* bad : {"", "1235", "246000", "126000", "123561", "12351a", "123519,5", "123519.2x"}) {
    EXPECT_FALSE(parseTimeOfDay(bad)) << bad;
  }
}

TEST(Fields, Latitude) {
  EXPECT_NEAR(*parseLatitude("4807.038", "N"), 48.0 + 7.038 / 60.0, 1e-12);
  EXPECT_NEAR(*parseLatitude("4807.038", "S"), -(48.0 + 7.038 / 60.0), 1e-12);
  EXPECT_NEAR(*parseLatitude("4134.49821229", "N"), 41.574970204833, 1e-11);  // survey grade
  EXPECT_DOUBLE_EQ(*parseLatitude("9000.000", "N"), 90.0);
  EXPECT_DOUBLE_EQ(*parseLatitude("0000.0000", "N"), 0.0);
  EXPECT_NEAR(*parseLatitude("0512.5", "N"), 5.0 + 12.5 / 60.0, 1e-12);
  EXPECT_FALSE(parseLatitude("9000.001", "N"));  // beyond the pole
  EXPECT_FALSE(parseLatitude("4860.000", "N"));  // 60 minutes
  EXPECT_FALSE(parseLatitude("4807.038", "E"));  // wrong hemisphere letter
  EXPECT_FALSE(parseLatitude("4807.038", ""));
  EXPECT_FALSE(parseLatitude("", "N"));
  EXPECT_FALSE(parseLatitude("48O7.038", "N"));
  EXPECT_FALSE(parseLatitude("-4807.038", "N"));
}

TEST(Fields, Longitude) {
  EXPECT_NEAR(*parseLongitude("01131.000", "E"), 11.0 + 31.0 / 60.0, 1e-12);
  EXPECT_NEAR(*parseLongitude("12311.12", "W"), -(123.0 + 11.12 / 60.0), 1e-12);
  EXPECT_DOUBLE_EQ(*parseLongitude("18000.000", "W"), -180.0);
  EXPECT_FALSE(parseLongitude("18000.001", "E"));
  EXPECT_FALSE(parseLongitude("01131.000", "N"));
}

TEST(Fields, Ddmmyy) {
  const auto d = parseDdmmyy("191194");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->day, 19);
  EXPECT_EQ(d->month, 11);
  EXPECT_EQ(d->yy, 94);
  for (const char* bad : {"", "320199", "001199", "011399", "2208-1", "19119", "1911944"}) {
    EXPECT_FALSE(parseDdmmyy(bad)) << bad;  // "2208-1": Telit HE910's year -1 (april6_2019.log)
  }
}

TEST(Fields, BearingWrapsNorth) {
  EXPECT_DOUBLE_EQ(*parseBearing("054.7"), 54.7);
  EXPECT_DOUBLE_EQ(*parseBearing("360.0"), 0.0);
  EXPECT_DOUBLE_EQ(*parseBearing("0"), 0.0);
  EXPECT_FALSE(parseBearing("-0.1"));
  EXPECT_FALSE(parseBearing("360.1"));
}

TEST(Fields, KnotIsExact) { EXPECT_DOUBLE_EQ(10.0 * kKnotToMps, 5.144444444444445); }

}  // namespace
}  // namespace headingd::nmea
