#include "headingd/can/units.hpp"

#include <numbers>

#include "headingd/core/angles.hpp"

namespace headingd::can {
namespace {

struct UnitEntry {
  Quantity quantity;
  std::string_view unit;
  double factor_to_si;
};

using core::kRadPerDeg;
constexpr double kStandardGravity = 9.80665;  // m/s², CGPM 1901

// Spellings seen in vendor DBC files; whitespace around the string is ignored by the caller.
constexpr UnitEntry kUnits[] = {
    {Quantity::angular_rate, "rad/s", 1.0},
    {Quantity::angular_rate, "rad/sec", 1.0},
    {Quantity::angular_rate, "mrad/s", 1e-3},
    {Quantity::angular_rate, "deg/s", kRadPerDeg},
    {Quantity::angular_rate, "deg/sec", kRadPerDeg},
    {Quantity::angular_rate, "degree/s", kRadPerDeg},
    {Quantity::angular_rate, "degrees/s", kRadPerDeg},
    {Quantity::angular_rate, "dps", kRadPerDeg},
    {Quantity::angular_rate, "\xC2\xB0/s", kRadPerDeg},    // °/s
    {Quantity::angular_rate, "\xC2\xB0/sec", kRadPerDeg},  // °/sec
    {Quantity::angular_rate, "\xB0/s", kRadPerDeg},        // °/s in Latin-1, as older DBC editors write it
    {Quantity::angular_rate, "mdps", 1e-3 * kRadPerDeg},
    {Quantity::acceleration, "m/s^2", 1.0},
    {Quantity::acceleration, "m/s2", 1.0},
    {Quantity::acceleration, "m/s**2", 1.0},
    {Quantity::acceleration, "m/s\xC2\xB2", 1.0},  // m/s²
    {Quantity::acceleration, "m/s\xB2", 1.0},      // m/s² in Latin-1
    {Quantity::acceleration, "mm/s^2", 1e-3},
    {Quantity::acceleration, "g", kStandardGravity},
    {Quantity::acceleration, "mg", 1e-3 * kStandardGravity},
    {Quantity::magnetic_field, "uT", 1.0},
    {Quantity::magnetic_field, "\xC2\xB5T", 1.0},  // µT (micro sign)
    {Quantity::magnetic_field, "\xCE\xBCT", 1.0},  // μT (Greek mu)
    {Quantity::magnetic_field, "microtesla", 1.0},
    {Quantity::magnetic_field, "nT", 1e-3},
    {Quantity::magnetic_field, "mT", 1e3},
    {Quantity::magnetic_field, "T", 1e6},
    {Quantity::magnetic_field, "G", 100.0},  // 1 gauss = 1e-4 T
    {Quantity::magnetic_field, "gauss", 100.0},
    {Quantity::magnetic_field, "Gauss", 100.0},
    {Quantity::magnetic_field, "mG", 0.1},
    {Quantity::magnetic_field, "mGauss", 0.1},
    {Quantity::magnetic_field, "milligauss", 0.1},
};

}  // namespace

const char* siUnitName(Quantity q) {
  switch (q) {
    case Quantity::angular_rate: return "rad/s";
    case Quantity::acceleration: return "m/s^2";
    case Quantity::magnetic_field: return "uT";
  }
  return "";
}

const char* quantityName(Quantity q) {
  switch (q) {
    case Quantity::angular_rate: return "angular rate";
    case Quantity::acceleration: return "acceleration";
    case Quantity::magnetic_field: return "magnetic field";
  }
  return "";
}

std::optional<double> unitFactorToSi(Quantity q, std::string_view unit) {
  while (!unit.empty() && (unit.front() == ' ' || unit.front() == '\t')) unit.remove_prefix(1);
  while (!unit.empty() && (unit.back() == ' ' || unit.back() == '\t')) unit.remove_suffix(1);
  for (const auto& e : kUnits) {
    if (e.quantity == q && e.unit == unit) return e.factor_to_si;
  }
  return std::nullopt;
}

const char* acceptedUnits(Quantity q) {
  switch (q) {
    case Quantity::angular_rate: return "rad/s, mrad/s, deg/s, dps, mdps, \xC2\xB0/s";
    case Quantity::acceleration: return "m/s^2, m/s2, mm/s^2, g, mg";
    case Quantity::magnetic_field: return "uT, \xC2\xB5T, nT, mT, T, G, gauss, mG, milligauss";
  }
  return "";
}

}  // namespace headingd::can
