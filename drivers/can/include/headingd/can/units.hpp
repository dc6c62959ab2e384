#pragma once
// Unit strings found in DBC files, and the factor that turns a value in that unit into the
// SI unit headingd uses inside (rad/s, m/s², µT), which the estimator's parameters assume.
#include <optional>
#include <string_view>

namespace headingd::can {

enum class Quantity { angular_rate, acceleration, magnetic_field };

const char* siUnitName(Quantity q);    // "rad/s", "m/s^2", "uT"
const char* quantityName(Quantity q);  // "angular rate", ...

// Multiply a value in `unit` by this to get the SI value; nullopt when the unit is not known
// for that quantity. Case matters where units differ only by case ("mg" milli-g, "mG" milligauss).
std::optional<double> unitFactorToSi(Quantity q, std::string_view unit);

// Comma-separated list of the units accepted for a quantity, for error messages.
const char* acceptedUnits(Quantity q);

}  // namespace headingd::can
