#include "headingd/core/gps_date_check.hpp"

#include <cmath>

namespace headingd::core {
namespace {

constexpr double kDaysPerYear = 365.25;
constexpr double kNsPerYear = kDaysPerYear * 86400.0 * 1e9;

}  // namespace

void GpsDateCheck::seed(double decimal_year) { seed_year_ = decimal_year; }

std::optional<double> GpsDateCheck::inUseAt(std::int64_t t_ns) const {
  if (!in_use_year_) return seed_year_;
  // In double: corrupt stamps may lie anywhere in the int64 range (found by fuzzing).
  return *in_use_year_ + (static_cast<double>(t_ns) - static_cast<double>(in_use_t_ns_)) / kNsPerYear;
}

void GpsDateCheck::use(double decimal_year, std::int64_t t_ns) {
  in_use_year_ = decimal_year;
  in_use_t_ns_ = t_ns;
  rival_year_.reset();
  rival_epochs_ = 0;
}

std::optional<double> GpsDateCheck::dateFor(double decimal_year, std::int64_t t_ns, bool* believed) {
  const std::optional<double> in_use = inUseAt(t_ns);
  const double tolerance_years = kToleranceDays / kDaysPerYear;
  if (wmm_->isDateWithinValidity(decimal_year)) {
    if (!in_use || std::abs(decimal_year - *in_use) <= tolerance_years) {
      use(decimal_year, t_ns);
      *believed = true;
      return decimal_year;
    }
    // Within the model's validity but far from the date in use: one of the two is wrong. A
    // date the epochs keep agreeing on replaces it in the end (the seed may be the wrong one).
    const bool agrees = rival_year_ && std::abs(decimal_year - *rival_year_) <= 1.0 / kDaysPerYear;
    rival_epochs_ = agrees ? rival_epochs_ + 1 : 1;
    rival_year_ = decimal_year;
    if (rival_epochs_ >= kEpochsToReplace) {
      use(decimal_year, t_ns);
      *believed = true;
      return decimal_year;
    }
  }
  *believed = false;
  ++not_believed_;
  // The date in use, carried by the epochs' time, may itself have left the model's validity
  // (a run of years, or stamps that jumped): then there is no date to evaluate it on.
  if (in_use && !wmm_->isDateWithinValidity(*in_use)) return std::nullopt;
  return in_use;
}

}  // namespace headingd::core
