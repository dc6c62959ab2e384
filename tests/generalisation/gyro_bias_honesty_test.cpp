// The gyro bias estimate is never learned wrong and never claims better than the data allow
// (issue 28 item 3): on every simulator scenario with a motion to score (the six phone
// scenarios: short opening rests, then carried, texting, calling, swinging, pocket, running;
// and the urban walk, run, crawl, §6.3 declination walk, shaking along an axis and any
// direction, hand-held and slow rotation) at the phone, consumer and mems grades, each
// component of the estimate's error against the true bias (offset plus drift, sensor axes)
// lies within 3 of its stated standard deviations in at least 99 % of the samples, at 100 and
// 50 Hz. Twelve seeds: the phone grade draws each axis's constant bias up to 6 deg/s, and seeds 9 and 12
// draw biases near or beyond the estimate's old clamp of 0.1 rad/s (seed 12: 0.112 rad/s in
// all), which held them 8-11 mrad/s wrong (37-97 % of their samples within 3 sigma). With the
// walk alone as the bias's drift (no bias instability, drifting_bias.hpp) hand-held, crawl
// and run at the phone grade failed in motion (seeds 7, 9, 6: 91.3, 98.2, 98.9 %).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "generalisation_support.hpp"
#include "headingd/sim/phone_scenarios.hpp"

namespace headingd::generalisation_test {
namespace {

constexpr double kMinShareWithin3Sigma = 0.99;

struct Honesty {
  double share_within_3_sigma = 0.0;
  double rms_error_rad_s = 0.0;
};

Honesty biasHonesty(const sim::SimResult& result) {
  const study::Recording r = study::fromSimulation(result, result.scenario.name);
  std::size_t within = 0, count = 0;
  double sum2 = 0.0;
  study::runEstimator(r, core::EstimatorParams{}, [&](std::size_t i, const core::Estimator& e) {
    if (!e.output().valid) return;
    const core::Vec3 error = e.gyroBias().bias() - result.imu[i].gyro_bias_rad_s;
    const core::Vec3 sigma = e.gyroBias().sigma();
    for (int axis = 0; axis < 3; ++axis) {
      ++count;
      if (std::abs(error[axis]) <= 3.0 * sigma[axis]) ++within;
    }
    sum2 += error.squaredNorm() / 3.0;
  });
  return {static_cast<double>(within) / static_cast<double>(count), std::sqrt(sum2 / static_cast<double>(count / 3))};
}

std::vector<std::string> motionScenarioNames() {
  std::vector<std::string> names = {"urban-walk", "run",       "crawl",    "thesis-declination",
                                    "shake",      "shake-any", "handheld", "slow-rotation"};
  for (std::string& name : sim::phoneScenarioNames()) names.push_back(std::move(name));
  return names;
}

class MotionClass : public ::testing::TestWithParam<std::tuple<std::string, sim::ImuGrade, double>> {};

TEST_P(MotionClass, TheBiasErrorLiesWithin3SigmaIn99PercentOfSamples) {
  const auto& [scenario, grade, rate_hz] = GetParam();
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const sim::SimResult result = sim::simulate(sim::simConfig(scenario, seed, grade, rate_hz), wmm());
    const Honesty h = biasHonesty(result);
    std::printf("%s seed %llu, %s, %.0f Hz: %.2f %% within 3 sigma, RMS error %.2f mrad/s\n", scenario.c_str(),
                static_cast<unsigned long long>(seed), sim::imuGradeName(grade), rate_hz,
                100.0 * h.share_within_3_sigma, 1e3 * h.rms_error_rad_s);
    EXPECT_GE(h.share_within_3_sigma, kMinShareWithin3Sigma) << scenario << " seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(GyroBiasHonesty, MotionClass,
                         ::testing::Combine(::testing::ValuesIn(motionScenarioNames()),
                                            ::testing::Values(sim::ImuGrade::kPhone, sim::ImuGrade::kConsumer,
                                                              sim::ImuGrade::kMems),
                                            ::testing::Values(100.0, 50.0)),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param) + "_" +
                                              sim::imuGradeName(std::get<1>(info.param)) + "_" +
                                              std::to_string(static_cast<int>(std::get<2>(info.param))) + "hz";
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace headingd::generalisation_test
