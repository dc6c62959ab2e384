#pragma once
// The World Magnetic Model evaluated from its Gauss coefficients: the main field at a
// geodetic position (WGS-84) and date, in the local north/east/down frame.
//
// Units here are those of the WMM (nT, degrees, km, decimal years), as in NOAA's test
// values; magneticFieldNed_uT() converts to the µT the estimator uses.
#include <memory>
#include <string>

#include "headingd/core/quaternion.hpp"
#include "headingd/core/wmm_coefficients.hpp"

namespace headingd::core {

struct GeodeticPosition {
  double latitude_deg = 0.0;   // geodetic, [-90, 90]
  double longitude_deg = 0.0;  // east positive, any finite value
  double height_km = 0.0;      // above the WGS-84 ellipsoid
};

// The field elements of the WMM report (NOAA/BGS technical report, section "Magnetic
// elements"): X north, Y east, Z down, H horizontal intensity, F total intensity,
// inclination I (positive down) and declination D (positive east of true north).
struct MagneticFieldElements {
  double x_nT = 0.0;
  double y_nT = 0.0;
  double z_nT = 0.0;
  double h_nT = 0.0;
  double f_nT = 0.0;
  double inclination_deg = 0.0;
  double declination_deg = 0.0;
  // False when the date is outside [epoch, epoch + 5 years]: the secular variation is
  // extrapolated there and the result degrades quickly.
  bool date_within_validity = false;
};

// The field as a NED vector in µT, the estimator's unit.
Vec3 magneticFieldNed_uT(const MagneticFieldElements& e);

// Decimal year of a calendar date as NOAA's WMM software computes it:
// year + (day_of_year - 1) / days_in_year, so 2025-01-01 is 2025.0.
// Throws std::invalid_argument for a date that does not exist (2025-02-29, month 13...).
double decimalYear(int year, int month, int day);

class WorldMagneticModel {
 public:
  // Throws std::invalid_argument if the coefficients are inconsistent (parseWmmCoefficients
  // output always is consistent).
  explicit WorldMagneticModel(const WmmCoefficients& coefficients);

  // Field at `position` on `decimal_year`. Throws std::invalid_argument for a non-finite
  // input or a latitude outside [-90, 90]; a date outside validity is evaluated anyway
  // (linear extrapolation) and flagged in the result.
  MagneticFieldElements field(const GeodeticPosition& position, double decimal_year) const;

  bool isDateWithinValidity(double decimal_year) const;
  double epochYear() const;
  double validUntilYear() const;  // epoch + 5 years
  const std::string& modelName() const;
  const std::string& releaseDate() const;
  int degree() const;

 private:
  struct Impl;
  // Immutable and shared: copies are cheap, and GeographicLib's coefficient views keep
  // pointing into vectors that never move.
  std::shared_ptr<const Impl> impl_;
};

}  // namespace headingd::core
