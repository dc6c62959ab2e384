#pragma once
// Shared by the simulator tests: the shipped WMM, runs cached per configuration (a run
// takes up to a second), and the files rendered to strings.
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "headingd/core/wmm.hpp"
#include "headingd/sim/output.hpp"
#include "headingd/sim/simulation.hpp"
#include "wmm_file.hpp"

namespace headingd::sim_test {

inline const core::WorldMagneticModel& shippedWmm() {
  static const core::WorldMagneticModel model = test::readWmmFile(HEADINGD_SIM_TEST_COF);
  return model;
}

inline sim::SimConfig config(const std::string& scenario, std::uint64_t seed = 1,
                             sim::ImuGrade grade = sim::ImuGrade::kConsumer, double rate_hz = 100.0) {
  return sim::simConfig(scenario, seed, grade, rate_hz);
}

// The same with point-sampled accelerometer and magnetometer: the sensor's reading at t_k is
// the true vector at t_k, for the tests of the relations between the signals and the truth.
inline sim::SimConfig pointConfig(const std::string& scenario, std::uint64_t seed = 1,
                                  sim::ImuGrade grade = sim::ImuGrade::kConsumer, double rate_hz = 100.0) {
  sim::SimConfig c = config(scenario, seed, grade, rate_hz);
  c.vector_sampling = sim::VectorSampling::kPoint;
  return c;
}

// Runs are cached by everything that distinguishes the configurations used here.
inline const sim::SimResult& run(const sim::SimConfig& c) {
  using Key = std::tuple<std::string, std::uint64_t, int, double, double, double, double, double, double, double,
                         double, int, int, int, int>;
  static std::map<Key, sim::SimResult> cache;
  const Key key{c.scenario,
                c.seed,
                static_cast<int>(c.imu_grade),
                c.imu_rate_hz,
                c.gps_rate_hz,
                c.mount_yaw_deg,
                c.mount_pitch_deg,
                c.mount_roll_deg,
                c.decl_anomaly_deg,
                c.origin.latitude_deg,
                c.origin.longitude_deg,
                c.year,
                c.month,
                c.day,
                static_cast<int>(c.vector_sampling)};
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, sim::simulate(c, shippedWmm())).first;
  return it->second;
}

template <typename Writer>
std::string render(const sim::SimResult& r, Writer write) {
  std::ostringstream out;
  write(out, r);
  return out.str();
}

inline std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

}  // namespace headingd::sim_test
