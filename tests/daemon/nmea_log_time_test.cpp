// Where NMEA log epochs lie on the log clock when a date is wrong: a receiver's 1980 default
// before its first fix, a week-number rollover. The log's day comes from its believable dates,
// a wrong date is counted and the fix keeps the day in use; midnight and multi-day logs still
// advance.
#include <gtest/gtest.h>

#include <vector>

#include "headingd/daemon/sources/nmea_log_time.hpp"

namespace headingd::daemon {
namespace {

constexpr std::int64_t kDay = NmeaLogTime::kDayNs;
constexpr std::int64_t kHour = kDay / 24;
constexpr std::int64_t k2026June1 = 20'605 * kDay;  // days since 1970-01-01
constexpr std::int64_t k1980Jan6 = 3'657 * kDay;

nmea::FixUpdate dated(std::int64_t day_ns, std::int64_t tod_ns) {
  nmea::FixUpdate u;
  u.fix.time_of_day_ns = tod_ns;
  u.fix.utc_ns = day_ns + tod_ns;
  return u;
}

nmea::FixUpdate undated(std::int64_t tod_ns) {
  nmea::FixUpdate u;
  u.fix.time_of_day_ns = tod_ns;
  return u;
}

TEST(NmeaLogTime, AWrongFirstDateDoesNotMoveTheLog) {
  std::vector<nmea::FixUpdate> log = {dated(k1980Jan6, 12 * kHour), undated(12 * kHour + 1),
                                      dated(k2026June1, 12 * kHour + 2), dated(k2026June1, 12 * kHour + 3)};
  const auto day = NmeaLogTime::logDayStart(log);
  ASSERT_TRUE(day.has_value());
  EXPECT_EQ(*day, k2026June1);
  NmeaLogTime time(0, day);
  for (std::int64_t i = 0; i < 4; ++i)
    EXPECT_EQ(time.of(log[static_cast<std::size_t>(i)].fix), k2026June1 + 12 * kHour + i);
  EXPECT_EQ(time.datesNotBelieved(), 1u);
}

TEST(NmeaLogTime, AWrongDateInTheMiddleIsCountedAndIgnored) {
  const std::vector<nmea::FixUpdate> log = {dated(k2026June1, kHour), dated(k2026June1 - 1024 * 7 * kDay, kHour + 1),
                                            dated(k2026June1, kHour + 2)};
  NmeaLogTime time(5, NmeaLogTime::logDayStart(log));
  EXPECT_EQ(time.of(log[0].fix), k2026June1 + kHour + 5);
  EXPECT_EQ(time.of(log[1].fix), k2026June1 + kHour + 1 + 5);
  EXPECT_EQ(time.of(log[2].fix), k2026June1 + kHour + 2 + 5);
  EXPECT_EQ(time.datesNotBelieved(), 1u);
}

TEST(NmeaLogTime, ALogOverSeveralDaysStartsOnItsFirstDay) {
  std::vector<nmea::FixUpdate> log;
  for (int day = 0; day < 3; ++day) {
    for (int hour = 0; hour < 24; hour += 6) log.push_back(dated(k2026June1 + day * kDay, hour * kHour));
  }
  log.push_back(undated(kHour));  // GGA-only after the last dated fix at 18:00 of day 3: midnight
  EXPECT_EQ(NmeaLogTime::logDayStart(log), k2026June1);
  NmeaLogTime time(0, NmeaLogTime::logDayStart(log));
  std::int64_t last = 0;
  for (const auto& u : log) {
    const std::int64_t t = *time.of(u.fix);
    EXPECT_GT(t, last);
    last = t;
  }
  EXPECT_EQ(last, k2026June1 + 3 * kDay + kHour);
  EXPECT_EQ(time.datesNotBelieved(), 0u);
}

TEST(NmeaLogTime, NoDateAnywhereStartsOn1970UntilOneComes) {
  const std::vector<nmea::FixUpdate> log = {undated(kHour), undated(2 * kHour)};
  EXPECT_FALSE(NmeaLogTime::logDayStart(log).has_value());
  NmeaLogTime time(0, std::nullopt);
  EXPECT_EQ(time.of(log[0].fix), kHour);
  EXPECT_EQ(time.of(dated(k2026June1, 3 * kHour).fix), k2026June1 + 3 * kHour);
  EXPECT_EQ(time.datesNotBelieved(), 0u);
}

}  // namespace
}  // namespace headingd::daemon
