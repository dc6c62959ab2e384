#pragma once
// Which GPS dates the World Magnetic Model is evaluated on. A receiver may send a date that
// parses but is not today: a default (1980-01-06) before its first fix, or one 1024 weeks
// back after a GPS week-number rollover. Evaluated there, the model's secular variation moves
// the declination by degrees and the true heading with it, silently.
//
// A date is believed when it lies within the model's validity and, once a date is in use (the
// configured place's, or an earlier believed one carried forward by the epochs' time), within
// kToleranceDays of it. A different date that kEpochsToReplace epochs running agree on (within
// a day of each other) replaces the one in use: the clock [place] took its date from was
// wrong, not the receiver. An epoch whose date is not believed is evaluated on the date in use.
#include <cstdint>
#include <optional>

#include "headingd/core/wmm.hpp"

namespace headingd::core {

class GpsDateCheck {
 public:
  static constexpr double kToleranceDays = 30.0;
  static constexpr int kEpochsToReplace = 30;

  // `wmm` is borrowed (its validity).
  explicit GpsDateCheck(const WorldMagneticModel& wmm) : wmm_(&wmm) {}

  // A date known to be right at the first GPS epoch (the configured place's).
  void seed(double decimal_year);
  // The date to evaluate the model on for an epoch at `t_ns` (the stream's time axis) whose
  // receiver sent `decimal_year`: that date when it is believed, else the date in use carried
  // to `t_ns`, else nullopt. `*believed` says which.
  std::optional<double> dateFor(double decimal_year, std::int64_t t_ns, bool* believed);

  std::uint64_t notBelieved() const { return not_believed_; }

 private:
  std::optional<double> inUseAt(std::int64_t t_ns) const;
  void use(double decimal_year, std::int64_t t_ns);

  const WorldMagneticModel* wmm_;
  std::optional<double> seed_year_;    // until the first epoch anchors it
  std::optional<double> in_use_year_;  // the date in use, at in_use_t_ns_
  std::int64_t in_use_t_ns_ = 0;
  std::optional<double> rival_year_;  // the date the epochs agree on against the one in use
  int rival_epochs_ = 0;
  std::uint64_t not_believed_ = 0;
};

}  // namespace headingd::core
