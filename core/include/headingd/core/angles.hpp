#pragma once
// Degrees and radians: the one place their factors are defined. Inside headingd angles are
// radians (DESIGN.md); degrees are for people, at the edges (configuration, CSV columns, logs,
// NMEA, reports). Named for their direction, so that a reader never has to look up which way
// a factor goes: degrees × kRadPerDeg = radians, radians × kDegPerRad = degrees.
#include <numbers>

namespace headingd::core {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace headingd::core
