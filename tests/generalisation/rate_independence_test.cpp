// The estimator behaves the same at any sample rate: BROAD's trials
// resampled to 100 and 50 Hz stay within 10 % of their error at the native 285.7 Hz, and the
// simulator's motions give the same errors at 50, 100, 200, 285.7 and 400 Hz.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <future>
#include <map>

#include "generalisation_support.hpp"
#include "headingd/study/resample.hpp"

namespace headingd::generalisation_test {
namespace {

struct Means {
  double total = 0.0, inclination = 0.0, aligned = 0.0;
  int n = 0;
  void add(const study::RunScore& s) {
    total += s.rmse.total_rad / kRadPerDeg;
    inclination += s.rmse.inclination_rad / kRadPerDeg;
    aligned += s.aligned_rmse.total_rad / kRadPerDeg;
    ++n;
  }
  Means mean() const { return {total / n, inclination / n, aligned / n, n}; }
};

void expectWithin(double value, double reference, double share, const std::string& what) {
  EXPECT_LE(std::abs(value / reference - 1.0), share) << what << ": " << value << " against " << reference;
}

TEST(RateIndependence, BroadResampledTo100And50HzStaysWithinTenPercentOfItsNativeError) {
  const std::vector<std::string> trials = broadTrials();
  ASSERT_FALSE(trials.empty());
  const std::vector<double> rates = {0.0, 100.0, 50.0};  // 0: as recorded
  std::vector<std::future<std::vector<study::RunScore>>> jobs;
  for (const std::string& path : trials) {
    jobs.push_back(std::async(std::launch::async, [&rates, path] {
      const study::Recording native = study::readBroadTrial(path);
      std::vector<study::RunScore> scores;
      for (const double rate : rates) {
        const study::Recording r = rate > 0.0 ? study::resample(native, rate) : native;
        scores.push_back(study::score(r, study::runEstimator(r, core::EstimatorParams{})));
      }
      return scores;
    }));
  }
  std::vector<Means> sums(rates.size());
  std::printf("%-45s  total deg (native / 100 / 50 Hz)   inclination deg\n", "trial");
  for (std::size_t t = 0; t < trials.size(); ++t) {
    const auto scores = jobs[t].get();
    for (std::size_t r = 0; r < rates.size(); ++r) sums[r].add(scores[r]);
    std::printf("%-45s  %5.2f %5.2f %5.2f                %5.2f %5.2f %5.2f\n",
                std::filesystem::path(trials[t]).filename().string().c_str(), scores[0].rmse.total_rad / kRadPerDeg,
                scores[1].rmse.total_rad / kRadPerDeg, scores[2].rmse.total_rad / kRadPerDeg,
                scores[0].rmse.inclination_rad / kRadPerDeg, scores[1].rmse.inclination_rad / kRadPerDeg,
                scores[2].rmse.inclination_rad / kRadPerDeg);
    // Tilt, trial by trial: within 15 % (or 0.05 deg, the figures' own spread).
    for (std::size_t r = 1; r < rates.size(); ++r) {
      const double native = scores[0].rmse.inclination_rad / kRadPerDeg,
                   resampled = scores[r].rmse.inclination_rad / kRadPerDeg;
      EXPECT_LE(std::abs(resampled - native), std::max(0.15 * native, 0.05))
          << trials[t] << " at " << rates[r] << " Hz";
    }
  }
  const Means native = sums[0].mean();
  for (std::size_t r = 1; r < rates.size(); ++r) {
    const Means m = sums[r].mean();
    std::printf("mean at %3.0f Hz: total %.3f (native %.3f), inclination %.3f (%.3f), aligned total %.3f (%.3f)\n",
                rates[r], m.total, native.total, m.inclination, native.inclination, m.aligned, native.aligned);
    const std::string at = std::to_string(static_cast<int>(rates[r])) + " Hz";
    expectWithin(m.total, native.total, 0.10, "mean total RMSE at " + at);
    expectWithin(m.inclination, native.inclination, 0.10, "mean inclination RMSE at " + at);
    expectWithin(m.aligned, native.aligned, 0.10, "mean aligned total RMSE at " + at);
  }
}

TEST(RateIndependence, SimulatedMotionsGiveTheSameErrorsAt50To400Hz) {
  // The current consumer-part noise (mems grade) on the four motion scenarios, 8 seeds each:
  // the pooled means at each rate against 285.7 Hz (BROAD's rate). Each rate draws its own
  // noise, so a scenario's mean alone moves by a few percent from rate to rate.
  const std::vector<std::string> scenarios = {"shake", "shake-any", "handheld", "slow-rotation"};
  const std::vector<double> rates = {50.0, 100.0, 200.0, 2000.0 / 7.0, 400.0};
  constexpr int kSeeds = 8;
  struct Run {
    study::RunScore score;
    study::EpisodeScore episode;
  };
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::future<Run>>> jobs;
  for (std::size_t s = 0; s < scenarios.size(); ++s) {
    for (std::size_t r = 0; r < rates.size(); ++r) {
      for (int seed = 1; seed <= kSeeds; ++seed) {
        jobs[{s, r}].push_back(std::async(std::launch::deferred, [&, s, r, seed] {
          const study::Recording rec = simulated(scenarios[s], seed, sim::ImuGrade::kMems, rates[r]);
          const auto est = study::runEstimator(rec, core::EstimatorParams{});
          return Run{study::score(rec, est), study::scoreEpisode(rec, est, 5.0, kRadPerDeg)};
        }));
      }
    }
  }
  // Two workers: each takes whole (scenario, rate) groups.
  std::vector<std::pair<std::size_t, std::size_t>> groups;
  for (const auto& [key, unused] : jobs) groups.push_back(key);
  std::map<std::pair<std::size_t, std::size_t>, std::vector<Run>> runs;
  std::mutex runs_mutex;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t g = next++; g < groups.size(); g = next++) {
      std::vector<Run> done;
      for (auto& f : jobs[groups[g]]) done.push_back(f.get());
      const std::lock_guard lock(runs_mutex);
      runs[groups[g]] = std::move(done);
    }
  };
  std::thread a(worker), b(worker);
  a.join();
  b.join();

  std::vector<Means> pooled(rates.size());
  std::printf("%-14s %6s  inclination deg (mean, worst during, worst 5 s after)   aligned total\n", "scenario", "Hz");
  for (std::size_t s = 0; s < scenarios.size(); ++s) {
    for (std::size_t r = 0; r < rates.size(); ++r) {
      Means m;
      double worst = 0.0, worst_after = 0.0;
      for (const Run& run : runs[{s, r}]) {
        m.add(run.score);
        pooled[r].add(run.score);
        worst = std::max(worst, run.episode.max_inclination_rad / kRadPerDeg);
        worst_after = std::max(worst_after, run.episode.max_inclination_after_rad / kRadPerDeg);
      }
      const Means mean = m.mean();
      std::printf("%-14s %6.1f  %5.2f %5.2f %5.2f                                %5.2f\n", scenarios[s].c_str(),
                  rates[r], mean.inclination, worst, worst_after, mean.aligned);
      // The tilt stays bounded at every rate (bounded_tilt_test.cpp asserts it over more seeds).
      EXPECT_LT(worst, 3.0) << scenarios[s] << " at " << rates[r] << " Hz";
      EXPECT_LT(worst_after, 1.0) << scenarios[s] << " at " << rates[r] << " Hz";
    }
  }
  const Means at_broad_rate = pooled[3].mean();
  for (std::size_t r = 0; r < rates.size(); ++r) {
    const Means m = pooled[r].mean();
    std::printf("pooled at %5.1f Hz: inclination %.3f, aligned total %.3f\n", rates[r], m.inclination, m.aligned);
    const std::string at = std::to_string(static_cast<int>(rates[r])) + " Hz";
    expectWithin(m.inclination, at_broad_rate.inclination, 0.10, "pooled inclination RMSE at " + at);
    expectWithin(m.aligned, at_broad_rate.aligned, 0.10, "pooled aligned total RMSE at " + at);
  }
}

}  // namespace
}  // namespace headingd::generalisation_test
