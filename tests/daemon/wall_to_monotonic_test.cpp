// WallToMonotonic: a CAN frame's wall-clock kernel stamp on the monotonic axis, when the wall
// clock is stepped between the stamping and the mapping.
#include <gtest/gtest.h>

#include "headingd/daemon/sources/wall_to_monotonic.hpp"

namespace headingd::daemon {
namespace {

constexpr std::int64_t kS = 1'000'000'000;
constexpr std::int64_t kHour = 3600 * kS;
constexpr std::int64_t kBoot = 1'780'315'200 * kS;  // wall time at monotonic 0

ClockReading at(std::int64_t realtime_ns, std::int64_t monotonic_ns, bool tight = true) {
  return {realtime_ns, monotonic_ns, tight};
}

TEST(WallToMonotonic, WithoutAStepItSubtractsTheOffsetAndFollowsSlewing) {
  WallToMonotonic m;
  EXPECT_EQ(m.map(kBoot + 10 * kS - 300'000, at(kBoot + 10 * kS, 10 * kS)), 10 * kS - 300'000);
  // NTP slewing: 20 us more offset a minute later; no step.
  EXPECT_EQ(m.map(kBoot + 70 * kS + 20'000 - 100, at(kBoot + 70 * kS + 20'000, 70 * kS)), 70 * kS - 100);
  EXPECT_EQ(m.steps(), 0u);
  // A frame that waited 2 s in the socket (the daemon was stopped) keeps its age.
  EXPECT_EQ(m.map(kBoot + 70 * kS + 20'000, at(kBoot + 72 * kS + 20'000, 72 * kS)), 70 * kS);
}

TEST(WallToMonotonic, AFrameStampedBeforeAStepKeepsItsTimeInBothDirections) {
  for (const std::int64_t step : {kHour, -kHour}) {
    WallToMonotonic m;
    EXPECT_EQ(m.map(kBoot + 10 * kS, at(kBoot + 10 * kS + 100, 10 * kS + 100)), 10 * kS);
    // Stamped at 11 s before the step, mapped after it.
    EXPECT_EQ(m.map(kBoot + 11 * kS, at(kBoot + step + 11 * kS + 50, 11 * kS + 50)), 11 * kS) << step;
    // Queued with it, mapped later still.
    EXPECT_EQ(m.map(kBoot + 11 * kS + 10, at(kBoot + step + 11 * kS + 80, 11 * kS + 80)), 11 * kS + 10) << step;
    // Stamped after the step.
    EXPECT_EQ(m.map(kBoot + step + 12 * kS, at(kBoot + step + 12 * kS + 100, 12 * kS + 100)), 12 * kS) << step;
    EXPECT_EQ(m.steps(), 1u);
    EXPECT_EQ(m.clamped(), 0u);
  }
}

TEST(WallToMonotonic, StepsThereAndBackAndAStampFromTheFutureIsClamped) {
  WallToMonotonic m;
  m.map(kBoot + kS, at(kBoot + kS, kS));
  EXPECT_EQ(m.map(kBoot + kHour + 2 * kS, at(kBoot + kHour + 2 * kS, 2 * kS)), 2 * kS);
  EXPECT_EQ(m.map(kBoot + 3 * kS, at(kBoot + 3 * kS, 3 * kS)), 3 * kS);
  EXPECT_EQ(m.steps(), 2u);
  // Later than now in every regime: now.
  EXPECT_EQ(m.map(kBoot + 2 * kHour, at(kBoot + 4 * kS, 4 * kS)), 4 * kS);
  EXPECT_EQ(m.clamped(), 1u);
}

TEST(WallToMonotonic, ALooseReadingIsNoStep) {
  // The thread was preempted between its clock reads: the offset it saw is off by that.
  WallToMonotonic m;
  m.map(kBoot + kS, at(kBoot + kS, kS));
  EXPECT_EQ(m.map(kBoot + 2 * kS, at(kBoot + 2 * kS + 5'000'000, 2 * kS, false)), 2 * kS);
  EXPECT_EQ(m.steps(), 0u);
}

TEST(WallToMonotonic, ReadClocksCarriesTheRealtimeReadingToTheEndOfItsBracket) {
  std::int64_t mono = 1000, real = kBoot;
  const ClockReading r = readClocks([&] { return mono += 40; }, [&] { return real; });
  EXPECT_TRUE(r.tight);
  EXPECT_EQ(r.monotonic_ns, 1080);
  EXPECT_EQ(r.realtime_ns - r.monotonic_ns, kBoot - 1060);  // read at monotonic 1060, mid-bracket
}

}  // namespace
}  // namespace headingd::daemon
