#pragma once
// Real files read whole, and the World Magnetic Model of a COF file: for the tests that use
// the shipped config/wmm/WMM2025.COF (each keeps one model for the process).
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "headingd/core/wmm.hpp"
#include "headingd/core/wmm_coefficients.hpp"

namespace headingd::test {

// The file's bytes; throws std::runtime_error naming the file when it cannot be opened.
inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The model of the COF file at `cof_path`, named by that path in parse errors.
inline core::WorldMagneticModel readWmmFile(const std::string& cof_path) {
  return core::WorldMagneticModel(core::parseWmmCoefficients(readFile(cof_path), cof_path));
}

}  // namespace headingd::test
