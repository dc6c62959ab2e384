// Bounded tilt: through sustained linear acceleration of any direction, up
// to 8 g and at 0.5-10 Hz, through vigorous hand-held handling and gentle slow rotation, the
// inclination error stays below 3 deg and is below 1 deg from 5 s after the motion ends; from
// any initial attitude error the estimator converges at rest within a stated time.
//
// The simulator's grades: `mems` has the white noise of current consumer 9-axis parts; both
// it and `consumer` keep a 2014 smartphone's bias instability (MAGYQ, 0.07 deg/s), so the
// gyro drifts more than a current part's would. `consumer` also has that phone's gyro noise,
// ~15 times a current part's (0.24 deg/s/√Hz): its angle random walk alone moves a 2 s tilt
// filter by ~0.5 deg RMS, and the same bounds are asserted for it with the margin that noise
// needs (below).
#include <gtest/gtest.h>

#include <cstdio>
#include <future>
#include <vector>

#include "generalisation_support.hpp"
#include "headingd/sim/motion_scenarios.hpp"

namespace headingd::generalisation_test {
namespace {

struct Bounds {
  double during_deg;
  double after_deg;
};
constexpr Bounds kIssueBounds{3.0, 1.0};
// The smartphone-noise gyro: measured worst 3.8 deg during, 1.8 deg after, over these seeds.
constexpr Bounds kNoisyGyroBounds{5.0, 2.5};

// Runs every recording on two threads and checks each against the bounds; prints a table.
void expectBounded(const std::vector<std::function<study::Recording()>>& makers, Bounds bounds,
                   const std::string& title) {
  std::vector<std::future<std::pair<std::string, study::EpisodeScore>>> jobs;
  std::vector<std::pair<std::string, study::EpisodeScore>> results(makers.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < makers.size(); i = next++) {
      const study::Recording r = makers[i]();
      results[i] = {r.name, episode(r)};
    }
  };
  std::thread a(worker), b(worker);
  a.join();
  b.join();
  double worst = 0.0, worst_after = 0.0, worst_settle = 0.0;
  for (const auto& [name, e] : results) {
    EXPECT_LT(e.max_inclination_rad / kRadPerDeg, bounds.during_deg) << name << ": during the motion";
    EXPECT_LT(e.max_inclination_after_rad / kRadPerDeg, bounds.after_deg) << name << ": from 5 s after it";
    worst = std::max(worst, e.max_inclination_rad / kRadPerDeg);
    worst_after = std::max(worst_after, e.max_inclination_after_rad / kRadPerDeg);
    worst_settle = std::max(worst_settle, e.settle_time_s);
  }
  std::printf(
      "%s: %zu runs, worst inclination error %.2f deg during the motion (bound %.1f), %.2f deg from 5 s "
      "after it (bound %.1f); below 1 deg for good at most %.1f s after the motion\n",
      title.c_str(), results.size(), worst, bounds.during_deg, worst_after, bounds.after_deg, worst_settle);
}

std::vector<std::function<study::Recording()>> seeds(const std::string& scenario, int count, sim::ImuGrade grade) {
  std::vector<std::function<study::Recording()>> makers;
  for (int seed = 1; seed <= count; ++seed) {
    makers.push_back([=] { return simulated(scenario, static_cast<std::uint64_t>(seed), grade); });
  }
  return makers;
}

TEST(BoundedTilt, SustainedAccelerationOfAnyDirectionUpTo8gAt05To10Hz) {
  // shake-any draws the attitude, the direction (uniform on the sphere), 0.5-10 Hz and
  // 0.5-8 g from the seed; 60 s of it with little rotation, held still before and after.
  expectBounded(seeds("shake-any", 100, sim::ImuGrade::kMems), kIssueBounds, "shake-any, mems, seeds 1-100");
}

TEST(BoundedTilt, ShakingAlongOneSensorAxis) {
  expectBounded(seeds("shake", 40, sim::ImuGrade::kMems), kIssueBounds, "shake, mems, seeds 1-40");
}

TEST(BoundedTilt, TheCornersOfTheRange) {
  // 8 g at the lowest and highest frequency, along each sensor axis and a diagonal.
  std::vector<std::function<study::Recording()>> makers;
  const core::Vec3 directions[] = {core::Vec3::UnitX(), core::Vec3::UnitY(), core::Vec3::UnitZ(),
                                   core::Vec3(1.0, -1.0, 1.0).normalized()};
  std::uint64_t seed = 100;
  for (const double hz : {0.5, 10.0}) {
    for (const core::Vec3& d : directions) {
      ++seed;
      makers.push_back([=] {
        sim::ShakeSpec spec;
        spec.initial_attitude = sim::uniformAttitude(seed, 7);
        spec.direction_body = d;
        spec.frequency_hz = hz;
        spec.peak_accel_m_s2 = 8.0 * 9.80665;
        char name[64];
        std::snprintf(name, sizeof name, "shake %.1f Hz 8 g", hz);
        return simulated(sim::shakeScenario(spec, name, name), seed, sim::ImuGrade::kMems);
      });
    }
  }
  expectBounded(makers, kIssueBounds, "8 g at 0.5 and 10 Hz along x, y, z and a diagonal, mems");
}

TEST(BoundedTilt, VigorousHandHeldHandling) {
  expectBounded(seeds("handheld", 40, sim::ImuGrade::kMems), kIssueBounds, "handheld, mems, seeds 1-40");
}

TEST(BoundedTilt, GentleSlowRotation) {
  expectBounded(seeds("slow-rotation", 40, sim::ImuGrade::kMems), kIssueBounds, "slow-rotation, mems, seeds 1-40");
}

TEST(BoundedTilt, WithASmartphoneNoiseGyro) {
  auto makers = seeds("shake-any", 40, sim::ImuGrade::kConsumer);
  for (const char* scenario : {"handheld", "slow-rotation"}) {
    const auto more = seeds(scenario, 20, sim::ImuGrade::kConsumer);
    makers.insert(makers.end(), more.begin(), more.end());
  }
  expectBounded(makers, kNoisyGyroBounds, "shake-any (40), handheld (20), slow-rotation (20), consumer");
}

TEST(BoundedTilt, ConvergesFromAnyInitialAttitudeErrorAtRest) {
  // The estimator starts from its first sample; turning that sample's accelerometer and
  // magnetometer starts it that far off (about a horizontal axis: all of it is tilt). The
  // sensor lies still, at any attitude, for 30 s. Stated: below 1 deg for good within 8 s;
  // with the smartphone-noise gyro below 2 deg within 10 s (its noise alone moves the tilt by
  // ~0.5 deg RMS, and its 1 deg/s offset is unknown until the first still block).
  double worst_s = 0.0;
  for (const auto grade : {sim::ImuGrade::kMems, sim::ImuGrade::kConsumer}) {
    const bool current_part = grade == sim::ImuGrade::kMems;
    const double settled_rad = (current_part ? 1.0 : 2.0) * kRadPerDeg;
    const double kStatedS = current_part ? 8.0 : 10.0;
    double grade_worst_s = 0.0;
    for (const double error_deg : {10.0, 45.0, 90.0, 135.0, 170.0, 179.0, 180.0}) {
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        sim::ShakeSpec still;  // no shake, no tremor, no drift: a sensor lying still
        still.initial_attitude = sim::uniformAttitude(seed, 11);
        still.peak_accel_m_s2 = 0.0;
        still.tremor_deg = still.hand_drift_deg = 0.0;
        still.still_before_s = 30.0;
        still.shake_s = still.still_after_s = 0.0;
        study::Recording r = simulated(sim::shakeScenario(still, "still", "still"), seed, grade);
        study::startOffBy(r, error_deg * kRadPerDeg, seed);
        const auto errors = study::perSampleErrors(r, study::runEstimator(r, core::EstimatorParams{}));
        double last_off_s = 0.0;  // the last time the error was at the bound or more
        for (std::size_t i = 0; i < r.size(); ++i) {
          if (errors[i].inclination_rad >= settled_rad) last_off_s = 1e-9 * static_cast<double>(r.samples[i].t_ns);
        }
        EXPECT_LT(last_off_s, kStatedS) << sim::imuGradeName(grade) << ", " << error_deg << " deg, seed " << seed;
        grade_worst_s = std::max(grade_worst_s, last_off_s);
      }
    }
    std::printf(
        "%s: from up to 180 deg off, lying still: below %.0f deg for good after at most %.1f s (stated %.0f s)\n",
        sim::imuGradeName(grade), settled_rad / kRadPerDeg, grade_worst_s, kStatedS);
    worst_s = std::max(worst_s, grade_worst_s);
  }
}

}  // namespace
}  // namespace headingd::generalisation_test
