#pragma once
// Shared by the generalisation tests: the World Magnetic Model, simulator runs as
// study::Recordings, the estimator run and scored on them, and the BROAD set to use.
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "headingd/core/angles.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/sim/simulation.hpp"
#include "headingd/study/recording.hpp"
#include "headingd/study/scoring.hpp"
#include "test_data.hpp"
#include "wmm_file.hpp"

namespace headingd::generalisation_test {

using core::kRadPerDeg;

inline const core::WorldMagneticModel& wmm() {
  static const core::WorldMagneticModel model = test::readWmmFile(HEADINGD_TEST_COF);
  return model;
}

inline study::Recording simulated(const std::string& scenario, std::uint64_t seed, sim::ImuGrade grade,
                                  double rate_hz = 100.0) {
  return study::fromSimulation(sim::simulate(sim::simConfig(scenario, seed, grade, rate_hz), wmm()),
                               scenario + " seed " + std::to_string(seed));
}

inline study::Recording simulated(const sim::Scenario& scenario, std::uint64_t seed, sim::ImuGrade grade,
                                  double rate_hz = 100.0) {
  return study::fromSimulation(sim::simulate(sim::simConfig(scenario.name, seed, grade, rate_hz), scenario, wmm()),
                               scenario.name + " seed " + std::to_string(seed));
}

// The motion episode of a run with the default estimator: its worst inclination error and
// the worst from 5 s after the motion's end, to check that it returns below 1 deg within 5 s.
inline study::EpisodeScore episode(const study::Recording& r) {
  return study::scoreEpisode(r, study::runEstimator(r, core::EstimatorParams{}), 5.0, 1.0 * kRadPerDeg);
}

// BROAD's trials: ../shared/data/broad's when it is beside the checkout, else the
// repository's subset (tests/data/broad); prints which (test_data.hpp).
inline std::vector<std::string> broadTrials() {
  std::vector<std::string> paths;
  for (const auto& p : test_data::all(test_data::kBroad)) paths.push_back(p.string());
  return paths;
}

}  // namespace headingd::generalisation_test
