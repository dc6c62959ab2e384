#pragma once
// Shared by the generalisation tests (issue 17): the World Magnetic Model, simulator runs as
// study::Recordings, the estimator run and scored on them, and the BROAD set to use.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/sim/simulation.hpp"
#include "headingd/study/recording.hpp"
#include "headingd/study/scoring.hpp"

namespace headingd::generalisation_test {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

inline const core::WorldMagneticModel& wmm() {
  static const core::WorldMagneticModel model = [] {
    std::ifstream in(HEADINGD_TEST_COF, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return core::WorldMagneticModel(core::parseWmmCoefficients(text.str(), HEADINGD_TEST_COF));
  }();
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
// the worst from 5 s after the motion's end, the "returns below 1 deg within 5 s".
inline study::EpisodeScore episode(const study::Recording& r) {
  return study::scoreEpisode(r, study::runEstimator(r, core::EstimatorParams{}), 5.0, 1.0 * kDeg);
}

// BROAD's trials: all 14 of ../shared/data/broad when it is beside the checkout, else the
// three in the repository (tests/data/broad and the demo's trial 05). `which` names the set.
inline std::vector<std::string> broadTrials(std::string* which) {
  std::vector<std::string> paths;
  const std::filesystem::path shared = std::filesystem::path(HEADINGD_SHARED_DIR) / "data" / "broad";
  const auto add = [&paths](const std::filesystem::path& dir, const std::string& prefix) {
    if (!std::filesystem::is_directory(dir)) return;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      const std::string f = e.path().filename().string();
      if (f.ends_with(".csv.gz") && f.starts_with(prefix)) paths.push_back(e.path().string());
    }
  };
  add(shared, "");
  if (!paths.empty()) {
    *which = "all " + std::to_string(paths.size()) + " trials of " + shared.string();
  } else {
    add(HEADINGD_TEST_DATA_DIR "/broad", "");
    add(HEADINGD_CONFIG_DIR "/demo", "05_");
    *which = "the repository's " + std::to_string(paths.size()) + " trials (tests/data/broad, config/demo; " +
             shared.string() + " is not there)";
  }
  std::sort(paths.begin(), paths.end(), [](const std::string& a, const std::string& b) {
    return std::filesystem::path(a).filename() < std::filesystem::path(b).filename();
  });
  return paths;
}

}  // namespace headingd::generalisation_test
