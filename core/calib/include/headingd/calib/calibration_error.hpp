#pragma once
// The one exception type of the calibration routines: the data cannot give the asked-for
// calibration (too few static segments, rotations that do not cover the sphere, a solver
// that does not converge). The message says what was missing, with the figure measured.
#include <stdexcept>
#include <string>

namespace headingd::calib {

struct CalibrationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace headingd::calib
