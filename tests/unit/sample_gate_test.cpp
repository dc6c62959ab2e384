// The sample gate: period from timestamps, and a verdict and a counter for every kind of bad
// sample (nothing is dropped silently).
#include "headingd/core/sample_gate.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "test_support.hpp"

namespace headingd::core {
namespace {

constexpr std::int64_t kMs = 1'000'000;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

ImuSample sampleAt(std::int64_t t_ns) {
  ImuSample s;
  s.t_ns = t_ns;
  s.gyro_rad_s = Vec3(0.01, 0.02, 0.03);
  s.accel_m_s2 = Vec3(0.0, 0.0, -9.81);
  s.mag_uT = Vec3(20.0, 0.0, 45.0);
  return s;
}

struct Checked {
  SampleVerdict verdict;
  double dt_s;
  bool mag_usable;
};

Checked check(SampleGate& gate, const ImuSample& s) {
  Checked c{SampleVerdict::kAccepted, -1.0, false};
  c.verdict = gate.check(s, &c.dt_s, &c.mag_usable);
  return c;
}

// The sample at `t_ns`, 10 ms after the last one the gate used: accepted, with that period
// (the time base went on from the last used sample, or restarted there).
void expectAcceptedTenMsLater(SampleGate& gate, std::int64_t t_ns) {
  const Checked next = check(gate, sampleAt(t_ns));
  EXPECT_EQ(next.verdict, SampleVerdict::kAccepted) << "sample at " << t_ns << " ns";
  EXPECT_DOUBLE_EQ(next.dt_s, 0.01) << "sample at " << t_ns << " ns";
}

TEST(SampleGate, PeriodComesFromTimestamps) {
  SampleGate gate(0.1);
  const Checked first = check(gate, sampleAt(1000 * kMs));
  EXPECT_EQ(first.verdict, SampleVerdict::kFirst);
  EXPECT_EQ(first.dt_s, 0.0);
  EXPECT_TRUE(first.mag_usable);

  // Irregular steps: 10 ms, 3.5 ms, 27 ms, 1 ns.
  std::int64_t t = 1000 * kMs;
  for (std::int64_t step : {10 * kMs, 3'500'000L, 27 * kMs, std::int64_t{1}}) {
    t += step;
    const Checked c = check(gate, sampleAt(t));
    EXPECT_EQ(c.verdict, SampleVerdict::kAccepted);
    EXPECT_DOUBLE_EQ(c.dt_s, static_cast<double>(step) * 1e-9);
    EXPECT_TRUE(c.mag_usable);
  }
  EXPECT_EQ(gate.counters().accepted, 4u);
}

TEST(SampleGate, StepOfExactlyTheGapLimitIsAccepted) {
  SampleGate gate(0.1);
  check(gate, sampleAt(0));
  const Checked c = check(gate, sampleAt(100 * kMs));
  EXPECT_EQ(c.verdict, SampleVerdict::kAccepted);
  EXPECT_DOUBLE_EQ(c.dt_s, 0.1);
  EXPECT_EQ(check(gate, sampleAt(200 * kMs + 1)).verdict, SampleVerdict::kGap);
}

TEST(SampleGate, DuplicateTimestampIsSkippedAndCounted) {
  SampleGate gate(0.1);
  check(gate, sampleAt(0));
  check(gate, sampleAt(10 * kMs));
  const Checked c = check(gate, sampleAt(10 * kMs));
  EXPECT_EQ(c.verdict, SampleVerdict::kDuplicateTime);
  EXPECT_EQ(c.dt_s, 0.0);
  EXPECT_EQ(gate.counters().duplicate_time, 1u);
  // The time base is unchanged: the next sample's period is from the last used one.
  expectAcceptedTenMsLater(gate, 20 * kMs);
}

TEST(SampleGate, SmallBackwardsStepIsSkippedAndCounted) {
  SampleGate gate(0.1);
  check(gate, sampleAt(0));
  check(gate, sampleAt(50 * kMs));
  const Checked c = check(gate, sampleAt(45 * kMs));
  EXPECT_EQ(c.verdict, SampleVerdict::kBackwardsTime);
  EXPECT_EQ(gate.counters().backwards_time, 1u);
  EXPECT_EQ(check(gate, sampleAt(-50 * kMs)).verdict, SampleVerdict::kBackwardsTime);  // exactly the limit back
  EXPECT_EQ(gate.counters().backwards_time, 2u);
  expectAcceptedTenMsLater(gate, 60 * kMs);  // from 50 ms, not from the skipped 45 ms
}

TEST(SampleGate, BigBackwardsStepIsAClockJumpThatRestartsTheTimeBase) {
  SampleGate gate(0.1);
  check(gate, sampleAt(10'000 * kMs));
  check(gate, sampleAt(10'010 * kMs));
  const Checked c = check(gate, sampleAt(5'000 * kMs));
  EXPECT_EQ(c.verdict, SampleVerdict::kClockJump);
  EXPECT_EQ(c.dt_s, 0.0);
  EXPECT_EQ(gate.counters().clock_jumps, 1u);
  expectAcceptedTenMsLater(gate, 5'010 * kMs);
}

TEST(SampleGate, BigForwardStepIsAGapThatRestartsTheTimeBase) {
  SampleGate gate(0.1);
  check(gate, sampleAt(0));
  const Checked c = check(gate, sampleAt(2'000 * kMs));
  EXPECT_EQ(c.verdict, SampleVerdict::kGap);
  EXPECT_EQ(c.dt_s, 0.0);  // the gyro is not integrated across the gap
  EXPECT_EQ(gate.counters().gaps, 1u);
  expectAcceptedTenMsLater(gate, 2'010 * kMs);
}

TEST(SampleGate, NonFiniteGyroOrAccelIsSkippedAndCounted) {
  SampleGate gate(0.1);
  check(gate, sampleAt(0));
  int n = 0;
  for (double bad : {kNaN, kInf, -kInf}) {
    for (int axis = 0; axis < 3; ++axis) {
      ImuSample g = sampleAt(10 * kMs);
      g.gyro_rad_s(axis) = bad;
      EXPECT_EQ(check(gate, g).verdict, SampleVerdict::kNonFinite);
      ImuSample a = sampleAt(10 * kMs);
      a.accel_m_s2(axis) = bad;
      EXPECT_EQ(check(gate, a).verdict, SampleVerdict::kNonFinite);
      n += 2;
    }
  }
  EXPECT_EQ(gate.counters().non_finite, static_cast<std::uint64_t>(n));
  // The skipped samples did not move the time base.
  expectAcceptedTenMsLater(gate, 10 * kMs);
}

TEST(SampleGate, NonFiniteFirstSampleDoesNotStartTheTimeBase) {
  SampleGate gate(0.1);
  ImuSample bad = sampleAt(0);
  bad.accel_m_s2.x() = kNaN;
  EXPECT_EQ(check(gate, bad).verdict, SampleVerdict::kNonFinite);
  EXPECT_EQ(check(gate, sampleAt(5 * kMs)).verdict, SampleVerdict::kFirst);
}

TEST(SampleGate, NonFiniteMagnetometerAloneIsAcceptedWithoutMag) {
  SampleGate gate(0.1);
  check(gate, sampleAt(0));
  ImuSample s = sampleAt(10 * kMs);
  s.mag_uT.y() = kNaN;
  const Checked c = check(gate, s);
  EXPECT_EQ(c.verdict, SampleVerdict::kAccepted);
  EXPECT_DOUBLE_EQ(c.dt_s, 0.01);
  EXPECT_FALSE(c.mag_usable);
  EXPECT_EQ(gate.counters().non_finite_mag, 1u);
  EXPECT_EQ(gate.counters().non_finite, 0u);
  EXPECT_EQ(gate.counters().accepted, 1u);

  s = sampleAt(20 * kMs);
  s.mag_uT.z() = -kInf;
  EXPECT_EQ(check(gate, s).verdict, SampleVerdict::kAccepted);
  EXPECT_EQ(gate.counters().non_finite_mag, 2u);
}

TEST(SampleGate, SampleWithoutMagnetometerIsNotCountedAsBadMag) {
  SampleGate gate(0.1);
  check(gate, sampleAt(0));
  ImuSample s = sampleAt(10 * kMs);
  s.has_mag = false;
  s.mag_uT = Vec3::Constant(kNaN);  // whatever is in there is not looked at
  const Checked c = check(gate, s);
  EXPECT_EQ(c.verdict, SampleVerdict::kAccepted);
  EXPECT_FALSE(c.mag_usable);
  EXPECT_EQ(gate.counters().non_finite_mag, 0u);
}

TEST(SampleGate, CountersAddUp) {
  SampleGate gate(0.1);
  const std::int64_t times[] = {0, 10, 10, 5, 20, 500, 510, -1000, -990, -990, -980};
  for (std::int64_t t : times) check(gate, sampleAt(t * kMs));
  const SampleCounters& c = gate.counters();
  EXPECT_EQ(c.accepted, 5u);  // 10, 20, 510, -990, -980
  EXPECT_EQ(c.duplicate_time, 2u);
  EXPECT_EQ(c.backwards_time, 1u);
  EXPECT_EQ(c.gaps, 1u);
  EXPECT_EQ(c.clock_jumps, 1u);
  EXPECT_EQ(c.non_finite, 0u);
}

TEST(SampleGate, ExtremeTimestampsAreJumpsNotSmallSteps) {
  // A corrupted timestamp can be anything an int64 holds (readImuCsv's llround of a huge t
  // gives INT64_MIN on x86). From the top of the range to the bottom is a clock jump, and back
  // up is a gap; neither may look like a short step.
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
  SampleGate gate(0.1);
  check(gate, sampleAt(kMax - 5));
  const Checked down = check(gate, sampleAt(kMin + 5));
  EXPECT_EQ(down.verdict, SampleVerdict::kClockJump) << sampleVerdictName(down.verdict) << " dt " << down.dt_s;
  const Checked up = check(gate, sampleAt(kMax - 5));
  EXPECT_EQ(up.verdict, SampleVerdict::kGap) << sampleVerdictName(up.verdict) << " dt " << up.dt_s;
  EXPECT_EQ(gate.counters().accepted, 0u);
}

TEST(SampleGate, VerdictNames) {
  EXPECT_STREQ(sampleVerdictName(SampleVerdict::kAccepted), "accepted");
  EXPECT_STREQ(sampleVerdictName(SampleVerdict::kGap), "gap");
  EXPECT_STREQ(sampleVerdictName(SampleVerdict::kClockJump), "clock_jump");
  EXPECT_STREQ(sampleVerdictName(SampleVerdict::kNonFinite), "non_finite");
}

}  // namespace
}  // namespace headingd::core
