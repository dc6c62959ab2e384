#pragma once
// gpsd's reports gathered into one nmea::Fix per receiver epoch, as the serial source's epoch
// assembler does with sentences, so that both sources feed the estimator the same epochs.
//
// gpsd may send several TPVs for one epoch: until it has learnt which sentence ends the
// receiver's cycle it reports after each one (a GGA gives a TPV with a position and a speed
// gpsd derived itself, the RMC after it one with the receiver's course and speed). TPVs with
// the same "time" are merged, each field taken from the latest report that has it; a TPV
// with another time, or quiet (completeEpoch), ends the epoch. A TPV without a time (gpsd
// has no date yet, or no fix) joins the epoch in progress. SKY reports carry the DOPs: one
// while an epoch is pending goes into it; one between epochs into the next.
#include <cstdint>
#include <functional>
#include <optional>

#include "headingd/gpsd/gpsd_report.hpp"
#include "headingd/nmea/fix.hpp"

namespace headingd::gpsd {

// One completed epoch, with the CLOCK_MONOTONIC time its last report arrived (as the serial
// source stamps an epoch with its last sentence's).
using EpochHandler = std::function<void(const nmea::Fix& fix, std::int64_t receive_ns)>;

class GpsdEpochMerger {
 public:
  explicit GpsdEpochMerger(EpochHandler on_epoch) : on_epoch_(std::move(on_epoch)) {}

  void addTpv(const nmea::Fix& fix, std::int64_t receive_ns);
  void addSky(const SkyReport& sky);
  // Delivers the epoch in progress, if any (the stream went quiet or ended).
  void completeEpoch();
  bool epochPending() const { return pending_.has_value(); }

  std::uint64_t epochs() const { return epochs_; }
  // TPVs of an epoch already delivered (they came after the quiet that ended it): dropped.
  std::uint64_t lateReports() const { return late_reports_; }

 private:
  EpochHandler on_epoch_;
  std::optional<nmea::Fix> pending_;
  std::int64_t pending_receive_ns_ = 0;
  std::optional<std::int64_t> delivered_utc_ns_;  // the time of the last epoch delivered
  SkyReport sky_between_;                         // a SKY that came while no epoch was pending
  std::uint64_t epochs_ = 0;
  std::uint64_t late_reports_ = 0;
};

}  // namespace headingd::gpsd
