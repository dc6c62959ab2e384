// Sensors as they come (issue 28 item 5): the simulator's phones sample the field 20-40 ms
// late at 25-50 Hz, repeated between samples. On each phone scenario the estimator learns
// that delay within 5 ms and uses it, or, where the phone's turns change too little for the
// gyro's noise (a phone held still in front or at the ear), learns nothing and keeps the
// default; and with it flags no more samples of the clean room's field as disturbed, fewer
// where the phone swings (a late field's dip swings with every turn of the phone).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "generalisation_support.hpp"
#include "headingd/sim/phone_scenarios.hpp"
#include "headingd/study/reference_delay.hpp"

namespace headingd::generalisation_test {
namespace {

// How late the fresh field samples reach their rows, on average: the drawn lag plus the
// time from the magnetometer's own sample to the row that first carries it.
double effectiveDelayS(const sim::SimResult& result) {
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 1; i < result.imu.size(); ++i) {
    if (result.imu[i].mag_truth_t_s == result.imu[i - 1].mag_truth_t_s) continue;
    sum += result.imu[i].t_s - result.imu[i].mag_truth_t_s;
    ++count;
  }
  return sum / count;
}

// How old the field each row carries is, on average over all rows (held rows included).
double meanFieldAgeS(const sim::SimResult& result) {
  double sum = 0.0;
  for (const auto& row : result.imu) sum += row.t_s - row.mag_truth_t_s;
  return sum / static_cast<double>(result.imu.size());
}

struct DelayRun {
  double candidate_s = 0.0;
  bool used = false;
  double disturbed_share = 0.0;
};

DelayRun runWith(const sim::SimResult& result, const core::EstimatorParams& params) {
  const study::Recording r = study::fromSimulation(result, result.scenario.name);
  std::size_t disturbed = 0, count = 0;
  DelayRun out;
  study::runEstimator(r, params, [&](std::size_t, const core::Estimator& e) {
    if (!e.output().valid) return;
    ++count;
    disturbed += e.output().mag_disturbed;
    out.candidate_s = e.magDelay().candidateS();
    out.used = e.magDelay().useCandidate();
  });
  out.disturbed_share = static_cast<double>(disturbed) / static_cast<double>(count);
  return out;
}

class PhoneScenario : public ::testing::TestWithParam<std::string> {};

TEST_P(PhoneScenario, TheMagnetometersDelayIsLearnedWhereTheTurnsShowIt) {
  const std::string scenario = GetParam();
  core::EstimatorParams without;
  without.mag_delay_max_s = 0.0;
  double disturbed_with = 0.0, disturbed_without = 0.0;
  int learned_runs = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const sim::SimResult result = sim::simulate(sim::simConfig(scenario, seed, sim::ImuGrade::kPhone, 100.0),
                                                sim::phoneScenario(scenario, seed), wmm());
    const double truth = effectiveDelayS(result);
    const DelayRun learned = runWith(result, core::EstimatorParams{});
    const DelayRun fixed = runWith(result, without);
    std::printf("%s seed %llu: delay %.1f ms (drawn lag %.1f ms), learned %.1f ms, %s; disturbed %.1f %% -> %.1f %%\n",
                scenario.c_str(), static_cast<unsigned long long>(seed), 1e3 * truth, 1e3 * result.timing.mag_lag_s,
                1e3 * learned.candidate_s, learned.used ? "used" : "not used", 100.0 * fixed.disturbed_share,
                100.0 * learned.disturbed_share);
    if (learned.candidate_s != 0.0) {
      EXPECT_NEAR(learned.candidate_s, truth, 0.005) << scenario << " seed " << seed;
      EXPECT_TRUE(learned.used) << scenario << " seed " << seed;
      ++learned_runs;
    }
    disturbed_with += learned.disturbed_share;
    disturbed_without += fixed.disturbed_share;
  }
  EXPECT_GE(learned_runs, 2) << scenario;
  EXPECT_LE(disturbed_with, disturbed_without * 1.02) << scenario;
}

INSTANTIATE_TEST_SUITE_P(MagDelay, PhoneScenario, ::testing::ValuesIn(sim::phoneScenarioNames()), [](const auto& info) {
  std::string name = info.param;
  for (char& c : name) {
    if (c == '-') c = '_';
  }
  return name;
});

// The study's check of the learned delay against a recording's reference
// (reference_delay.hpp) finds the simulated phone's: the age of the field the rows carry,
// and the interval-mean gyro half a sample late.
TEST(ReferenceDelays, FoundAsSimulatedOnSwingingAndRunningPhones) {
  for (const std::string scenario : {"phone-swinging", "phone-running"}) {
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const sim::SimResult result = sim::simulate(sim::simConfig(scenario, seed, sim::ImuGrade::kPhone, 100.0),
                                                  sim::phoneScenario(scenario, seed), wmm());
      const study::ReferenceDelays d = study::measureReferenceDelays(study::fromSimulation(result, scenario));
      const double age = meanFieldAgeS(result);
      std::printf("%s seed %llu: field %.0f ms (its mean age %.1f ms), gyro %.0f ms\n", scenario.c_str(),
                  static_cast<unsigned long long>(seed), 1e3 * d.mag_s, 1e3 * age, 1e3 * d.gyro_s);
      ASSERT_TRUE(d.valid);
      EXPECT_NEAR(d.mag_s, age, 0.005) << scenario << " seed " << seed;
      EXPECT_NEAR(d.gyro_s, 0.005, 0.0015) << scenario << " seed " << seed;
      EXPECT_LT(d.mag_spread_uT, d.mag_spread_at_zero_uT);
    }
  }
}

}  // namespace
}  // namespace headingd::generalisation_test
