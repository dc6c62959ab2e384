#pragma once
// Helpers shared by the WMM tests: real files, read whole.
#include <string>

#include "headingd/core/wmm.hpp"
#include "test_data.hpp"
#include "wmm_file.hpp"

namespace headingd::wmm_test {

using test::readFile;

// A file of NOAA's reference data (../shared/data/wmm, else tests/data/wmm), announced.
inline std::string referenceFile(const std::string& name) { return test_data::file(test_data::kWmm, name).string(); }

// The model as shipped (config/wmm/WMM2025.COF).
inline const core::WorldMagneticModel& shippedModel() {
  static const core::WorldMagneticModel model = test::readWmmFile(HEADINGD_WMM_CONFIG_COF);
  return model;
}

}  // namespace headingd::wmm_test
