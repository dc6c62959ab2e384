#include "headingd/core/wmm.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/SphericalHarmonic1.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "headingd/core/angles.hpp"

namespace headingd::core {
namespace {

// Geomagnetic reference radius of the WMM (NOAA/BGS WMM technical report): the a in
// V = a Σ (a/r)^(n+1) Σ (g cos mλ + h sin mλ) P_n^m(sin φ').
constexpr double kWmmReferenceRadius_m = 6371200.0;
// The secular variation is a linear fit valid for five years from the epoch.
constexpr double kValidityYears = 5.0;

using GeographicLib::SphericalEngine;

// GeographicLib stores C (cosine, with m = 0) and S (sine, without m = 0) by columns of
// constant m: C[m N - m (m - 1) / 2 + n], S at the same index minus (N + 1).
struct HarmonicTables {
  std::vector<double> c, s, c_rate, s_rate;
};

HarmonicTables layoutTables(const WmmCoefficients& k) {
  const int N = k.degree;
  if (!std::isfinite(k.epoch_year)) throw std::invalid_argument("WorldMagneticModel: epoch must be finite");
  if (N < 1 || N > kWmmMaxDegree) {
    throw std::invalid_argument("WorldMagneticModel: degree must be 1.." + std::to_string(kWmmMaxDegree));
  }
  // GeographicLib grows a process-wide table of square roots when coefficients are set up,
  // which races with other threads evaluating. Sizing it once (thread-safe static
  // initialisation) for every degree we accept makes later growth a no-op.
  static const bool kRootTableReady = (SphericalEngine::RootTable(kWmmMaxDegree), true);
  (void)kRootTableReady;
  const auto c_size = static_cast<std::size_t>(SphericalEngine::coeff::Csize(N, N));
  const auto s_size = static_cast<std::size_t>(SphericalEngine::coeff::Ssize(N, N));
  HarmonicTables t{std::vector<double>(c_size, 0.0), std::vector<double>(s_size, 0.0), std::vector<double>(c_size, 0.0),
                   std::vector<double>(s_size, 0.0)};
  for (const WmmTerm& term : k.terms) {
    if (term.n < 1 || term.n > N || term.m < 0 || term.m > term.n) {
      throw std::invalid_argument("WorldMagneticModel: coefficient (n, m) outside the model's degree");
    }
    const int idx = term.m * N - term.m * (term.m - 1) / 2 + term.n;
    t.c[static_cast<std::size_t>(idx)] = term.g_nT;
    t.c_rate[static_cast<std::size_t>(idx)] = term.g_rate_nT_per_year;
    if (term.m > 0) {
      t.s[static_cast<std::size_t>(idx - (N + 1))] = term.h_nT;
      t.s_rate[static_cast<std::size_t>(idx - (N + 1))] = term.h_rate_nT_per_year;
    }
  }
  return t;
}

}  // namespace

struct WorldMagneticModel::Impl {
  explicit Impl(const WmmCoefficients& k)
      : epoch_year(k.epoch_year),
        model_name(k.model_name),
        release_date(k.release_date),
        degree(k.degree),
        tables(layoutTables(k)),
        // Value(tau) = Σ (a/r)^(n+1) [(g + tau ġ) cos mλ + (h + tau ḣ) sin mλ] P̄_nm, with
        // Schmidt semi-normalised P̄_nm, the normalisation of the WMM's Gauss coefficients.
        harmonic(tables.c, tables.s, degree, tables.c_rate, tables.s_rate, degree, kWmmReferenceRadius_m,
                 GeographicLib::SphericalHarmonic1::SCHMIDT) {}

  double epoch_year;
  std::string model_name;
  std::string release_date;
  int degree;
  HarmonicTables tables;  // must outlive and precede `harmonic`, which points into it
  GeographicLib::SphericalHarmonic1 harmonic;
};

WorldMagneticModel::WorldMagneticModel(const WmmCoefficients& coefficients)
    : impl_(std::make_shared<const Impl>(coefficients)) {}

MagneticFieldElements WorldMagneticModel::field(const GeodeticPosition& position, double decimal_year) const {
  if (!std::isfinite(position.latitude_deg) || position.latitude_deg < -90.0 || position.latitude_deg > 90.0) {
    throw std::invalid_argument("WMM: latitude must be within [-90, 90] degrees");
  }
  if (!std::isfinite(position.longitude_deg)) throw std::invalid_argument("WMM: longitude must be finite");
  if (!std::isfinite(position.height_km)) throw std::invalid_argument("WMM: height must be finite");
  if (!std::isfinite(decimal_year)) throw std::invalid_argument("WMM: date must be finite");

  // Geodetic (WGS-84) to Earth-centred Earth-fixed; M maps local east/north/up vectors to
  // geocentric ones (v_geo = M v_enu, row-major).
  double px = 0.0, py = 0.0, pz = 0.0;
  std::vector<double> M(9);
  GeographicLib::Geocentric::WGS84().Forward(position.latitude_deg, position.longitude_deg, position.height_km * 1000.0,
                                             px, py, pz, M);

  // B = -∇V and V = a · Value, so the geocentric field is -a times the gradient (nT/m · m).
  double gx = 0.0, gy = 0.0, gz = 0.0;
  impl_->harmonic(decimal_year - impl_->epoch_year, px, py, pz, gx, gy, gz);
  const double bx = -kWmmReferenceRadius_m * gx;
  const double by = -kWmmReferenceRadius_m * gy;
  const double bz = -kWmmReferenceRadius_m * gz;

  // Into the geodetic local frame with M's transpose; this is the WMM's rotation from
  // geocentric to geodetic latitude done in one step.
  const double east = M[0] * bx + M[3] * by + M[6] * bz;
  const double north = M[1] * bx + M[4] * by + M[7] * bz;
  const double up = M[2] * bx + M[5] * by + M[8] * bz;

  MagneticFieldElements e;
  e.x_nT = north;
  e.y_nT = east;
  e.z_nT = -up;
  e.h_nT = std::hypot(e.x_nT, e.y_nT);
  e.f_nT = std::hypot(e.h_nT, e.z_nT);
  e.inclination_deg = std::atan2(e.z_nT, e.h_nT) * kDegPerRad;
  e.declination_deg = std::atan2(e.y_nT, e.x_nT) * kDegPerRad;
  e.date_within_validity = isDateWithinValidity(decimal_year);
  return e;
}

bool WorldMagneticModel::isDateWithinValidity(double decimal_year) const {
  return decimal_year >= epochYear() && decimal_year <= validUntilYear();
}

double WorldMagneticModel::epochYear() const { return impl_->epoch_year; }
double WorldMagneticModel::validUntilYear() const { return impl_->epoch_year + kValidityYears; }
const std::string& WorldMagneticModel::modelName() const { return impl_->model_name; }
const std::string& WorldMagneticModel::releaseDate() const { return impl_->release_date; }
int WorldMagneticModel::degree() const { return impl_->degree; }

Vec3 magneticFieldNed_uT(const MagneticFieldElements& e) {
  constexpr double kMicroTeslaPerNanoTesla = 1e-3;
  return Vec3(e.x_nT, e.y_nT, e.z_nT) * kMicroTeslaPerNanoTesla;
}

double decimalYear(int year, int month, int day) {
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  static constexpr int kDaysInMonth[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month < 1 || month > 12) throw std::invalid_argument("month must be 1..12");
  const int days_this_month = kDaysInMonth[month - 1] + (month == 2 && leap ? 1 : 0);
  if (day < 1 || day > days_this_month) {
    throw std::invalid_argument("day must be 1.." + std::to_string(days_this_month) + " for that month");
  }
  int day_of_year = day;
  for (int i = 0; i < month - 1; ++i) day_of_year += kDaysInMonth[i];
  if (leap && month > 2) ++day_of_year;
  return year + (day_of_year - 1) / (leap ? 366.0 : 365.0);
}

}  // namespace headingd::core
