#include <gtest/gtest.h>

#include <chrono>

#include "headingd/nmea/fix_accumulator.hpp"
#include "nmea_test_support.hpp"

namespace headingd::nmea {
namespace {

using test::decodeOk;

constexpr std::int64_t kS = 1'000'000'000;
constexpr std::int64_t kDay = 86'400 * kS;

std::int64_t daysSince1970(int y, unsigned m, unsigned d) {
  return std::chrono::sys_days{std::chrono::year{y} / m / d}.time_since_epoch().count();
}

const std::int64_t kMar18_2020 = daysSince1970(2020, 3, 18);

class Accumulate : public ::testing::Test {
 protected:
  const Fix& apply(std::string_view body) {
    acc.apply(decodeOk(body));
    return acc.fix();
  }
  FixAccumulator acc;
};

TEST_F(Accumulate, SentencesOfOneEpochAddUp) {
  apply("GPGGA,132820.60,4134.49821229,N,09345.03351845,W,2,09,1.0,278.020,M,-31.442,M,7.6,0133");
  const Fix& f = apply("GPRMC,132820.60,A,4134.49821229,N,09345.03351845,W,3.252,92.308,180320,11.5985,E,D");
  EXPECT_NEAR(f.position->lat_deg, 41.574970205, 1e-9);
  EXPECT_DOUBLE_EQ(*f.alt_msl_m, 278.020);
  EXPECT_DOUBLE_EQ(*f.geoid_separation_m, -31.442);
  EXPECT_DOUBLE_EQ(*f.course_deg, 92.308);
  EXPECT_NEAR(*f.speed_mps, 1.673, 5e-4);
  EXPECT_DOUBLE_EQ(*f.magvar_deg, 11.5985);
  EXPECT_EQ(*f.quality, 2);
  EXPECT_EQ(*f.satellites_used, 9);
  EXPECT_DOUBLE_EQ(*f.hdop, 1.0);
  EXPECT_EQ(*f.mode, FixMode::k3D);
  EXPECT_EQ(*f.utc_ns, kMar18_2020 * kDay + (13 * 3600 + 28 * 60 + 20) * kS + 600'000'000);
}

TEST_F(Accumulate, ANewTimeOfDayStartsAFreshEpoch) {
  apply("GPRMC,132820.60,A,4134.49821229,N,09345.03351845,W,3.252,92.308,180320,11.5985,E,D");
  apply("GPVTG,92.3,T,,M,3.2,N,,K,D");
  const Fix& f = apply("GPGGA,132821.60,4134.49822493,N,09345.03347183,W,2,09,1.0,277.995,M,-31.442,M,7.6,0133");
  // No course or speed from the previous second next to this second's position.
  EXPECT_FALSE(f.course_deg);
  EXPECT_FALSE(f.speed_mps);
  EXPECT_FALSE(f.magvar_deg);
  EXPECT_NEAR(f.position->lat_deg, 41.574970416, 1e-9);
  EXPECT_EQ(*f.time_of_day_ns, (13 * 3600 + 28 * 60 + 21) * kS + 600'000'000);
  // The date carries over from the RMC.
  EXPECT_EQ(*f.utc_ns / kDay, kMar18_2020);
}

TEST_F(Accumulate, StampsWithin10msAreOneEpoch) {
  apply("GPRMC,120000.000,A,4807.038,N,01131.000,E,1.0,45.0,180320,,");
  EXPECT_TRUE(apply("GPGGA,120000.005,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,").course_deg);
  EXPECT_FALSE(apply("GPGGA,120000.020,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,").course_deg);
}

TEST_F(Accumulate, UntimedSentencesJoinTheCurrentEpoch) {
  apply("GPGGA,120000,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
  apply("GPVTG,054.7,T,034.4,M,005.5,N,010.2,K,A");
  apply("GPGSA,A,2,03,07,08,,,,,,,,,,3.6,2.0,3.0");
  const Fix& f = apply("GPHDT,341.8,T");
  EXPECT_DOUBLE_EQ(*f.course_deg, 54.7);
  EXPECT_DOUBLE_EQ(*f.speed_mps, 5.5 * kKnotToMps);
  EXPECT_EQ(*f.mode, FixMode::k2D);  // the receiver's own word beats "altitude present"
  EXPECT_DOUBLE_EQ(*f.pdop, 3.6);
  EXPECT_DOUBLE_EQ(*f.heading_deg, 341.8);
}

TEST_F(Accumulate, ModeFromPositionSentencesWithoutGsa) {
  EXPECT_EQ(*apply("GPRMC,120000,A,4807.038,N,01131.000,E,1.0,45.0,180320,,").mode, FixMode::k2D);
  EXPECT_EQ(*apply("GPGGA,120000,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,").mode, FixMode::k3D);
  EXPECT_EQ(*apply("GPGGA,120001,4807.038,N,01131.000,E,1,08,0.9,,M,,M,,").mode, FixMode::k2D);
}

TEST_F(Accumulate, QualityZeroIsNoFix) {
  apply("GPRMC,071734.929,A,4404.1178,N,12118.8608,W,0.0,0.0,111111,,");
  // tr737A+.log: quality 0 with a position; gpsd shows it, we do not.
  const Fix& f = apply("GPGGA,071734.929,4404.1178,N,12118.8608,W,0,4,,1127.8,M,-19.6,M,,");
  EXPECT_EQ(*f.mode, FixMode::kNoFix);
  EXPECT_FALSE(f.position);
  EXPECT_FALSE(f.alt_msl_m);
  EXPECT_FALSE(f.speed_mps);
  EXPECT_EQ(*f.quality, 0);
}

TEST_F(Accumulate, RmcWarningAndModeNAreNoFix) {
  EXPECT_EQ(*apply("GPRMC,125106,V,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W,S").mode, FixMode::kNoFix);
  EXPECT_FALSE(acc.fix().position);
  EXPECT_FALSE(acc.fix().utc_ns);  // dates under status V are not trusted
  EXPECT_EQ(*apply("GPRMC,125107,A,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W,N").mode, FixMode::kNoFix);
  EXPECT_TRUE(apply("GPRMC,125108,A,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W,A").position);
}

TEST_F(Accumulate, LaterValidSentenceRestoresTheFix) {
  // GPSmap-76S.log: RMC V, then GGA quality 8 (simulator) in the same second.
  apply("GPRMC,125106,V,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W,S");
  const Fix& f = apply("GPGGA,125106,3854.5087,N,07726.4523,W,8,10,2.0,268.8,M,-33.9,M,,");
  EXPECT_EQ(*f.mode, FixMode::k3D);
  EXPECT_NEAR(f.position->lat_deg, 38.908478333, 1e-9);
  EXPECT_EQ(*f.quality, 8);
}

TEST_F(Accumulate, VtgIgnoredWhenNotValidOrWithoutFix) {
  apply("GPGGA,120000,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
  EXPECT_FALSE(apply("GPVTG,054.7,T,,M,005.5,N,,K,N").course_deg);
  apply("GPGGA,120001,,,,,0,00,,,M,,M,,");
  EXPECT_FALSE(apply("GPVTG,054.7,T,,M,005.5,N,,K").speed_mps);
}

TEST_F(Accumulate, GnsAnyConstellationWithAFixCounts) {
  const Fix& f = apply("GNGNS,053232.438,3114.8789,N,12135.2442,E,ANNA,07,1.2,153.8,8.3,,0000");
  EXPECT_NEAR(f.position->lat_deg, 31.248, 1e-4);
  EXPECT_EQ(*f.mode, FixMode::k3D);
  EXPECT_EQ(*f.satellites_used, 7);
  EXPECT_EQ(*apply("GNGNS,053233.438,,,,,NNNN,00,,,0.0,,0000").mode, FixMode::kNoFix);
}

TEST_F(Accumulate, GnsNavigationStatusVNeitherSetsNorClears) {
  // quectel-eg25-g.log sends V with every fix; the GGA before it is a good fix.
  apply("GPGGA,191504.01,3645.876678,N,03124.668626,E,1,04,1.1,-14.1,M,32.0,M,,");
  const Fix& f = apply("GNGNS,191504.01,3645.000000,N,03124.000000,E,AAN,09,1.1,-14.1,32.0,,,V");
  EXPECT_NEAR(f.position->lat_deg, 36.764611300, 1e-9);
  EXPECT_EQ(*f.mode, FixMode::k3D);
}

TEST_F(Accumulate, GllMarksTheEpoch) {
  // ericsson-gru04.log sends GLL, VTG, ZDA, GNS: the VTG belongs with the GNS.
  apply("GNGLL,4111.59880,N,11156.56667,W,170600.000,A,A");
  apply("GNVTG,000.0,T,348.3,M,000.0,N,000.0,K,A");
  apply("GNZDA,170600.000,06,02,2026,,");
  const Fix& f = apply("GNGNS,170600.000,4111.59880,N,11156.56667,W,AANN,21,0.53,01443.9,-016.5,,");
  EXPECT_DOUBLE_EQ(*f.course_deg, 0.0);
  EXPECT_DOUBLE_EQ(*f.speed_mps, 0.0);
  EXPECT_DOUBLE_EQ(*f.alt_msl_m, 1443.9);
}

TEST_F(Accumulate, TwoDigitYearTakesTheCenturyFromContext) {
  // Before any ZDA: 20xx, whatever the two digits (gpsd would make 94 into 1994).
  EXPECT_EQ(*apply("GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E").utc_ns / kDay,
            daysSince1970(2094, 11, 19));
  // A ZDA's four-digit year sets the century for later RMCs.
  apply("GPZDA,225447,19,11,1994,00,00");
  EXPECT_EQ(*apply("GPRMC,225448,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E").utc_ns / kDay,
            daysSince1970(1994, 11, 19));
}

TEST_F(Accumulate, DatelessSentencesRollOverAtMidnight) {
  apply("GPRMC,235959.5,A,4807.038,N,01131.000,E,1.0,45.0,311299,,");
  const std::int64_t dec31 = daysSince1970(2099, 12, 31);
  EXPECT_EQ(*acc.fix().utc_ns, dec31 * kDay + (86'399 * kS) + 500'000'000);
  const Fix& f = apply("GPGGA,000000.5,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
  EXPECT_EQ(*f.utc_ns, (dec31 + 1) * kDay + 500'000'000);
  // And again the next midnight, without another RMC.
  apply("GPGGA,120000,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
  apply("GPGGA,235959,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
  EXPECT_EQ(*apply("GPGGA,000001,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,").utc_ns,
            (dec31 + 2) * kDay + 1 * kS);
}

TEST_F(Accumulate, WithoutADateThereIsNoUtc) {
  const Fix& f = apply("GPGGA,120000,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,");
  EXPECT_TRUE(f.time_of_day_ns);
  EXPECT_FALSE(f.utc_ns);
}

TEST_F(Accumulate, GstSigmas) {
  apply("GPGGA,172814.0,4807.038,N,01131.000,E,4,08,0.9,545.4,M,46.9,M,,");
  const Fix& f = apply("GPGST,172814.0,0.006,0.023,0.020,273.6,0.023,0.020,0.031");
  EXPECT_DOUBLE_EQ(*f.lat_sigma_m, 0.023);
  EXPECT_DOUBLE_EQ(*f.lon_sigma_m, 0.020);
  EXPECT_DOUBLE_EQ(*f.alt_sigma_m, 0.031);
  EXPECT_TRUE(f.position);  // GST's stamp does not start an epoch
}

}  // namespace
}  // namespace headingd::nmea
