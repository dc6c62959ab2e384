// TPV and SKY reports gathered into one fix per receiver epoch.
#include <gtest/gtest.h>

#include <vector>

#include "headingd/gpsd/gpsd_epoch_merger.hpp"

namespace headingd::gpsd {
namespace {

struct Delivered {
  nmea::Fix fix;
  std::int64_t receive_ns;
};

nmea::Fix tpv(const char* line) { return std::get<TpvReport>(parseGpsdReport(line)).fix; }

// What gpsd 3.22 sends for a receiver's GGA then RMC of one epoch before it has learnt the
// cycle: a TPV after each, the first with a speed of its own making and its model's variation.
TEST(GpsdEpochMerger, TwoTpvsOfOneTimeAreOneEpochWithTheLaterValues) {
  std::vector<Delivered> out;
  GpsdEpochMerger m([&](const nmea::Fix& f, std::int64_t t) { out.push_back({f, t}); });
  m.addTpv(
      tpv(R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:13.000Z","lat":59.33,"lon":18.07,"magvar":6.4,"speed":1.966})"),
      100);
  m.addSky(std::get<SkyReport>(parseGpsdReport(R"({"class":"SKY","hdop":1.07,"uSat":8})")));
  m.addTpv(
      tpv(R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:13.000Z","lat":59.33,"lon":18.07,"track":33.36,"magvar":7.7,"speed":1.295})"),
      200);
  EXPECT_TRUE(out.empty());
  m.addTpv(tpv(R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:14.000Z","lat":59.34,"lon":18.07})"), 300);
  ASSERT_EQ(out.size(), 1u);
  const nmea::Fix& f = out[0].fix;
  EXPECT_EQ(out[0].receive_ns, 200);  // the epoch's last report
  EXPECT_DOUBLE_EQ(*f.speed_mps, 1.295);
  EXPECT_DOUBLE_EQ(*f.course_deg, 33.36);
  EXPECT_DOUBLE_EQ(*f.magvar_deg, 7.7);
  EXPECT_DOUBLE_EQ(*f.hdop, 1.07);
  EXPECT_EQ(*f.satellites_used, 8);
  m.completeEpoch();  // quiet: the 12:00:14 epoch goes out
  ASSERT_EQ(out.size(), 2u);
  EXPECT_DOUBLE_EQ(out[1].fix.position->lat_deg, 59.34);
  EXPECT_FALSE(out[1].fix.hdop);  // a DOP is not carried over from another epoch
  EXPECT_EQ(m.epochs(), 2u);
}

TEST(GpsdEpochMerger, ATpvWithoutTimeJoinsTheEpochAndALateOneIsCounted) {
  std::vector<Delivered> out;
  GpsdEpochMerger m([&](const nmea::Fix& f, std::int64_t t) { out.push_back({f, t}); });
  m.addTpv(tpv(R"({"class":"TPV","mode":3,"lat":59.33,"lon":18.07})"), 1);
  m.addTpv(tpv(R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:13.000Z","track":10.0})"), 2);
  m.completeEpoch();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].fix.position && out[0].fix.course_deg && out[0].fix.utc_ns);
  // A report of the epoch after it went out (gpsd slower than epoch_idle_s): dropped, counted.
  m.addTpv(tpv(R"({"class":"TPV","mode":3,"time":"2026-06-01T12:00:13.000Z","speed":1.0})"), 3);
  m.completeEpoch();
  EXPECT_EQ(out.size(), 1u);
  EXPECT_EQ(m.lateReports(), 1u);
}

TEST(GpsdEpochMerger, ASkyBetweenEpochsGoesIntoTheNext) {
  std::vector<Delivered> out;
  GpsdEpochMerger m([&](const nmea::Fix& f, std::int64_t t) { out.push_back({f, t}); });
  m.addSky(std::get<SkyReport>(parseGpsdReport(R"({"class":"SKY","hdop":0.9})")));
  m.addTpv(tpv(R"({"class":"TPV","mode":1})"), 5);
  m.completeEpoch();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(*out[0].fix.hdop, 0.9);
  EXPECT_EQ(*out[0].fix.mode, nmea::FixMode::kNoFix);
}

}  // namespace
}  // namespace headingd::gpsd
