#pragma once
// Shared by the calibration tests: the shipped WMM, simulator runs cached per configuration,
// and the columns the calibration routines take.
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "headingd/core/imu_sample.hpp"
#include "headingd/core/wmm.hpp"
#include "headingd/sim/simulation.hpp"
#include "wmm_file.hpp"

namespace headingd::calib_test {

inline const core::WorldMagneticModel& shippedWmm() {
  static const core::WorldMagneticModel model = test::readWmmFile(HEADINGD_CALIB_TEST_COF);
  return model;
}

inline const sim::SimResult& simulated(const std::string& scenario, std::uint64_t seed,
                                       sim::ImuGrade grade = sim::ImuGrade::kUncalibrated) {
  using Key = std::tuple<std::string, std::uint64_t, int>;
  static std::map<Key, sim::SimResult> cache;
  const Key key{scenario, seed, static_cast<int>(grade)};
  auto it = cache.find(key);
  if (it == cache.end()) {
    sim::SimConfig c;
    c.scenario = scenario;
    c.seed = seed;
    c.imu_grade = grade;
    it = cache.emplace(key, sim::simulate(c, shippedWmm())).first;
  }
  return it->second;
}

inline std::vector<core::ImuSample> samplesOf(const sim::SimResult& r) {
  std::vector<core::ImuSample> out;
  out.reserve(r.imu.size());
  for (const sim::ImuRow& row : r.imu) out.push_back(sim::imuSample(row));
  return out;
}

inline std::vector<core::Vec3> magOf(const sim::SimResult& r) {
  std::vector<core::Vec3> out;
  out.reserve(r.imu.size());
  for (const sim::ImuRow& row : r.imu) out.push_back(row.mag_uT);
  return out;
}

inline double fieldNorm(const sim::SimResult& r) { return r.wmm.f_nT / 1000.0; }

}  // namespace headingd::calib_test
