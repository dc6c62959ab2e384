// gps.nmea: framing and checksums, the epoch/time alignment with the IMU time axis, fix and
// no-fix sentences, the receiver's magnetic variation, and course behaviour.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "headingd/sim/nmea_writer.hpp"
#include "sim_test_support.hpp"

namespace headingd::sim_test {
namespace {

// Splits "$...*HH\r\n" sentences; checks framing and checksum of each.
std::vector<std::vector<std::string>> parseSentences(const std::string& text) {
  std::vector<std::vector<std::string>> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = text.find("\r\n", pos);
    EXPECT_NE(end, std::string::npos) << "every sentence ends in CRLF";
    if (end == std::string::npos) break;
    const std::string line = text.substr(pos, end - pos);
    pos = end + 2;
    EXPECT_EQ(line.front(), '$');
    const std::size_t star = line.rfind('*');
    EXPECT_EQ(star, line.size() - 3) << line;
    const std::string body = line.substr(1, star - 1);
    unsigned x = 0;
    for (const char c : body) x ^= static_cast<unsigned char>(c);
    EXPECT_EQ(std::strtoul(line.substr(star + 1).c_str(), nullptr, 16), x) << line;
    EXPECT_NE(line.substr(star + 1).find_first_of("0123456789ABCDEF"), std::string::npos);
    EXPECT_LE(line.size(), 82u) << "NMEA 0183 limit including CRLF is 82: " << line;
    out.push_back(splitFields(body));
  }
  return out;
}

// Seconds after 12:00:00 of "hhmmss.ss".
double secondsAfterNoon(const std::string& hhmmss) {
  return std::stod(hhmmss.substr(0, 2)) * 3600.0 + std::stod(hhmmss.substr(2, 2)) * 60.0 + std::stod(hhmmss.substr(4)) -
         12.0 * 3600.0;
}

TEST(Nmea, ChecksumOfAKnownSentence) {
  // A sentence from the NMEA literature with its published checksum.
  EXPECT_EQ(sim::nmeaSentence("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"),
            "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n");
}

TEST(Nmea, EveryLineIsFramedAndChecksummed) {
  for (const char* scenario : {"urban-walk", "thesis-declination"}) {
    const sim::SimResult& r = run(config(scenario, 4, sim::ImuGrade::kConsumer, 50.0));
    const auto sentences = parseSentences(render(r, sim::writeNmea));
    EXPECT_EQ(sentences.size(), 3 * r.gps.size()) << scenario;
  }
}

TEST(Nmea, EpochsAreOnTheImuTimeAxisInTimeOrder) {
  sim::SimConfig c = config("crawl", 4, sim::ImuGrade::kConsumer, 50.0);
  c.gps_rate_hz = 5.0;
  const sim::SimResult& r = run(c);
  const auto sentences = parseSentences(render(r, sim::writeNmea));
  ASSERT_EQ(r.gps.size(), static_cast<std::size_t>(r.scenario.durationS() * 5.0) + 1);
  for (std::size_t i = 0; i < sentences.size(); ++i) {
    const std::size_t epoch = i / 3;
    const char* type = i % 3 == 0 ? "GPGGA" : (i % 3 == 1 ? "GPRMC" : "GPVTG");
    ASSERT_EQ(sentences[i][0], type);
    if (i % 3 == 2) continue;  // VTG carries no time
    // t = UTC - (date 12:00:00), and epoch j is at j / rate.
    EXPECT_NEAR(secondsAfterNoon(sentences[i][1]), static_cast<double>(epoch) / 5.0, 1e-9);
    EXPECT_NEAR(r.gps[epoch].t_s, static_cast<double>(epoch) / 5.0, 1e-12);
  }
  EXPECT_EQ(sentences[1][9], "010626");  // RMC date of --date 2026-06-01
}

TEST(Nmea, NoFixIndoorsWithQualityZeroAndStatusV) {
  const sim::SimResult& r = run(config("urban-walk", 4, sim::ImuGrade::kConsumer, 50.0));
  const auto sentences = parseSentences(render(r, sim::writeNmea));
  std::size_t no_fix = 0, fix = 0;
  for (std::size_t e = 0; e < r.gps.size(); ++e) {
    const auto& gga = sentences[3 * e];
    const auto& rmc = sentences[3 * e + 1];
    const bool indoor = r.scenario.phases[sim::phaseAt(r.scenario, r.gps[e].t_s).index].indoor;
    if (indoor) {
      EXPECT_FALSE(r.gps[e].fix) << "t = " << r.gps[e].t_s;
    }
    if (r.gps[e].fix) {
      ++fix;
      EXPECT_EQ(gga[6], "1");
      EXPECT_EQ(rmc[2], "A");
      EXPECT_FALSE(gga[2].empty());
    } else {
      ++no_fix;
      EXPECT_EQ(gga[6], "0");
      EXPECT_EQ(rmc[2], "V");
      EXPECT_TRUE(gga[2].empty());
      EXPECT_TRUE(rmc[3].empty());
    }
  }
  EXPECT_GT(no_fix, 200u);  // two buildings, 205 s indoors
  EXPECT_GT(fix, 300u);
}

TEST(Nmea, RmcCarriesTheWmmVariationAndPositionMatchesTruth) {
  sim::SimConfig c = config("thesis-declination", 4, sim::ImuGrade::kConsumer, 50.0);
  c.decl_anomaly_deg = 3.0;  // local truth; the receiver only knows the WMM
  const sim::SimResult& r = run(c);
  const auto sentences = parseSentences(render(r, sim::writeNmea));
  char expected[16];
  std::snprintf(expected, sizeof expected, "%.1f", r.wmm.declination_deg);
  const auto& rmc = sentences[1];
  EXPECT_EQ(rmc[10], expected);
  EXPECT_EQ(rmc[11], r.wmm.declination_deg >= 0.0 ? "E" : "W");
  // Position ddmm.mmmmm: within the receiver's error of the truth (a few metres).
  for (std::size_t e = 0; e < r.gps.size(); e += 10) {
    const auto& gga = sentences[3 * e];
    const double lat = std::stod(gga[2].substr(0, 2)) + std::stod(gga[2].substr(2)) / 60.0;
    const double lon = std::stod(gga[4].substr(0, 3)) + std::stod(gga[4].substr(3)) / 60.0;
    EXPECT_NEAR(lat, r.gps[e].true_position.latitude_deg, 15.0 / 111e3);
    EXPECT_NEAR(lon, r.gps[e].true_position.longitude_deg, 15.0 / 56e3);
    EXPECT_NEAR(lat, r.gps[e].position.latitude_deg, 1e-7);  // rounding of 1e-5 minute
  }
}

TEST(Nmea, CourseFollowsTheWalkAndIsHeldWhenStanding) {
  const sim::SimResult& r = run(config("thesis-declination", 4, sim::ImuGrade::kConsumer, 50.0));
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  std::optional<double> previous_course;
  for (const sim::GpsEpoch& e : r.gps) {
    ASSERT_TRUE(e.fix);  // clean sky in this scenario
    if (e.true_speed_mps > 1.0) {
      ASSERT_TRUE(e.course_deg.has_value());
      const double d = std::remainder(*e.course_deg - e.true_course_deg, 360.0);
      sum += d;
      sum2 += d * d;
      ++n;
    }
    // Below the static-hold speed the receiver reports 0 and keeps the last course.
    if (e.speed_mps == 0.0 && previous_course) {
      EXPECT_EQ(e.course_deg, previous_course) << "t = " << e.t_s;
    }
    if (e.t_s < 10.0) {
      EXPECT_FALSE(e.course_deg.has_value()) << "no course before the first walk";
    }
    if (e.t_s == 66.0) {
      // Standing after the first walk (north), turned east in place: still the walk's course.
      ASSERT_TRUE(e.course_deg.has_value());
      EXPECT_LT(std::abs(std::remainder(*e.course_deg, 360.0)), 20.0);
    }
    previous_course = e.course_deg;
  }
  ASSERT_GT(n, 150);
  const double rms = std::sqrt(sum2 / n);
  EXPECT_GT(rms, 1.0);  // consumer receiver: a few degrees at walking speed
  EXPECT_LT(rms, 8.0);
  EXPECT_LT(std::abs(sum / n), 1.5);
}

TEST(Nmea, UtcRollsOverMidnightIntoTheNextDate) {
  const sim::UtcClock clock{2026, 12, 31, 12.0 * 3600.0};
  EXPECT_EQ(sim::utcAt(clock, 0.0).hhmmss, "120000.00");
  EXPECT_EQ(sim::utcAt(clock, 0.1).hhmmss, "120000.10");
  const sim::UtcStamp next = sim::utcAt(clock, 12.0 * 3600.0 + 61.5);
  EXPECT_EQ(next.hhmmss, "000101.50");
  EXPECT_EQ(next.ddmmyy, "010127");
}

}  // namespace
}  // namespace headingd::sim_test
