// The published heading 1-sigma (core/heading_uncertainty.hpp) is never over-confident: in
// every simulator scenario class with a motion, at the mems and consumer grades (seeds 1-6:
// with three, one seed's residual hard iron, a 2.4-sigma draw of the floor, decides a class),
// and on the BROAD trials, at least 90 % of the heading errors lie within 2 sigma. (Issue 28
// asks for 90-97 %; the upper end is not met in most classes, 68 of the 84 over seeds 1-30:
// the floor of the field's error is what a sensor that keeps one attitude needs, and most
// classes turn and see their residual averaged: docs/heading-sigma.md has the figures.)
// Simulations are scored plainly (their truth is in the estimator's magnetic frame); a BROAD
// trial after the constant earth and body rotations are fitted (its reference has its own
// north), as headingd-study does.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "generalisation_support.hpp"

namespace headingd::generalisation_test {
namespace {

constexpr double kMinShareWithin2Sigma = 0.90;

double shareWithin2Sigma(const study::Recording& r, bool fit_alignment) {
  std::vector<double> sigmas;
  sigmas.reserve(r.size());
  const auto estimates = study::runEstimator(r, core::EstimatorParams{}, [&](std::size_t, const core::Estimator& e) {
    sigmas.push_back(e.output().heading_sigma_rad);
  });
  return study::headingCoverage(r, fit_alignment ? study::alignedEstimates(r, estimates) : estimates, sigmas, 2.0);
}

class SimulatedClass : public ::testing::TestWithParam<std::tuple<const char*, sim::ImuGrade>> {};

TEST_P(SimulatedClass, AtLeast90PercentOfHeadingErrorsLieWithin2Sigma) {
  const auto [scenario, grade] = GetParam();
  double sum = 0.0;
  const std::vector<std::uint64_t> seeds = {1, 2, 3, 4, 5, 6};
  for (const std::uint64_t seed : seeds) sum += shareWithin2Sigma(simulated(scenario, seed, grade), false);
  const double share = sum / static_cast<double>(seeds.size());
  std::printf("%s, %s: %.1f %% of heading errors within 2 sigma\n", scenario, sim::imuGradeName(grade), 100.0 * share);
  EXPECT_GE(share, kMinShareWithin2Sigma);
}

INSTANTIATE_TEST_SUITE_P(HeadingSigma, SimulatedClass,
                         ::testing::Combine(::testing::Values("urban-walk", "run", "crawl", "thesis-declination",
                                                              "shake", "handheld", "slow-rotation"),
                                            ::testing::Values(sim::ImuGrade::kMems, sim::ImuGrade::kConsumer)),
                         [](const auto& info) {
                           std::string name =
                               std::string(std::get<0>(info.param)) + "_" + sim::imuGradeName(std::get<1>(info.param));
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

// A sensor shaken in place hardly turns, so its calibration's residual hard iron makes one
// field error for the whole run, which the sigma must cover as such (heading_field_turn_rad:
// decorrelating with time, the model let the observer average it, and shake and shake-any
// mems were at 88.9 / 89.0 % over these seeds; now 96.6 %). One draw per run: 30 seeds.
TEST(HeadingSigma, ASensorShakenInPlaceKeepsOneFieldErrorAndTheSigmaCoversIt) {
  for (const char* scenario : {"shake", "shake-any"}) {
    for (const sim::ImuGrade grade : {sim::ImuGrade::kMems, sim::ImuGrade::kConsumer}) {
      double sum = 0.0;
      constexpr int kSeeds = 30;
      for (int seed = 1; seed <= kSeeds; ++seed) {
        sum += shareWithin2Sigma(simulated(scenario, static_cast<std::uint64_t>(seed), grade), false);
      }
      const double share = sum / kSeeds;
      std::printf("%s, %s, seeds 1-30: %.1f %% within 2 sigma\n", scenario, sim::imuGradeName(grade), 100.0 * share);
      EXPECT_GE(share, kMinShareWithin2Sigma) << scenario << ", " << sim::imuGradeName(grade);
    }
  }
}

TEST(HeadingSigma, OnBroadAtLeast90PercentOfHeadingErrorsLieWithin2Sigma) {
  double sum = 0.0;
  const auto trials = broadTrials();
  ASSERT_FALSE(trials.empty());
  for (const auto& path : trials) {
    const double share = shareWithin2Sigma(study::readBroadTrial(path), true);
    std::printf("%s: %.1f %%\n", path.c_str(), 100.0 * share);
    sum += share;
  }
  EXPECT_GE(sum / static_cast<double>(trials.size()), kMinShareWithin2Sigma);
}

}  // namespace
}  // namespace headingd::generalisation_test
