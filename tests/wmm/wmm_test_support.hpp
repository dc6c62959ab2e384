#pragma once
// Helpers shared by the WMM tests: real files, read whole.
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "headingd/core/wmm.hpp"

namespace headingd::wmm_test {

inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The model as shipped (config/wmm/WMM2025.COF).
inline const core::WorldMagneticModel& shippedModel() {
  static const core::WorldMagneticModel model(
      core::parseWmmCoefficients(readFile(HEADINGD_WMM_CONFIG_COF), HEADINGD_WMM_CONFIG_COF));
  return model;
}

}  // namespace headingd::wmm_test
