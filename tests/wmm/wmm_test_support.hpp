#pragma once
// Helpers shared by the WMM tests: real files, read whole.
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "headingd/core/wmm.hpp"
#include "test_data.hpp"

namespace headingd::wmm_test {

inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A file of NOAA's reference data (../shared/data/wmm, else tests/data/wmm), announced.
inline std::string referenceFile(const std::string& name) { return test_data::file(test_data::kWmm, name).string(); }

// The model as shipped (config/wmm/WMM2025.COF).
inline const core::WorldMagneticModel& shippedModel() {
  static const core::WorldMagneticModel model(
      core::parseWmmCoefficients(readFile(HEADINGD_WMM_CONFIG_COF), HEADINGD_WMM_CONFIG_COF));
  return model;
}

}  // namespace headingd::wmm_test
