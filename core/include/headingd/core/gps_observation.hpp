#pragma once
// What the estimator needs from one GPS epoch, on the IMU's time axis (the reader that turns
// NMEA into these decides the alignment). Angles in radians, true north.
#include <cstdint>
#include <optional>

#include "headingd/core/wmm.hpp"

namespace headingd::core {

struct GpsObservation {
  std::int64_t t_ns = 0;  // IMU time axis
  bool fix_ok = false;    // 2D/3D fix with a valid position
  std::optional<GeodeticPosition> position;
  std::optional<double> decimal_year;  // from the receiver's UTC date
  std::optional<double> course_rad;    // over ground, from true north
  std::optional<double> speed_mps;
  std::optional<double> hdop;
  std::optional<double> magvar_rad;  // receiver's magnetic variation (RMC), east positive
};

}  // namespace headingd::core
