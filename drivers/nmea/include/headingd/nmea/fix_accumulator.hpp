#pragma once
// Builds the Fix of the current epoch from decoded sentences.
//
// Epochs: a receiver sends a burst of sentences per fix (GGA, RMC, GSA, VTG, ...), several of
// them stamped with the fix's UTC time of day. A stamped sentence whose time differs from
// the current epoch's starts a new epoch and clears the Fix; unstamped ones (VTG, GSA, HDT)
// belong to the epoch in progress. gpsd draws its reporting cycles the same way, which is
// why a course from one second is never reported with the position of the next.
//
// Validity: a GGA with quality 0, an RMC or GLL with status V or mode N, a GNS whose
// constellations are all N say "no fix": mode becomes kNoFix and the epoch's position,
// altitude, course and speed are dropped. Only valid sentences set them. A GNS with
// navigation status V is not used, but does not clear the fix either: Quectel sends V with
// every fix (quectel-eg25-g.log, GGA quality 1 in the same epoch).
#include <cstdint>
#include <optional>

#include "headingd/nmea/fix.hpp"
#include "headingd/nmea/sentences.hpp"

namespace headingd::nmea {

struct FixAccumulatorConfig {
  // RMC sends a two-digit year; the century comes from context, as in gpsd's NMEA driver:
  // the last ZDA's four-digit year, and before any ZDA this one (20xx). (gpsd 3.2x now
  // pivots at 69 instead, making 69..99 into 19xx; GPS receivers of interest postdate 2000.)
  int default_century = 2000;
  // Stamps closer than this are the same epoch (receivers print 2 or 3 decimals).
  std::int64_t same_epoch_tolerance_ns = 10'000'000;
};

class FixAccumulator {
 public:
  explicit FixAccumulator(FixAccumulatorConfig config = {});

  void apply(const DecodedSentence& s);
  const Fix& fix() const { return fix_; }

 private:
  struct CivilDate {
    int year = 0;
    int month = 0;
    int day = 0;
  };

  void applyGga(const Gga& g);
  void applyRmc(const Rmc& r);
  void applyVtg(const Vtg& v);
  void applyGns(const Gns& g);
  void applyGsa(const Gsa& g);
  void applyGst(const Gst& g);
  void applyHdt(const Hdt& h);
  void applyZda(const Zda& z);
  void applyGll(const Gll& g);

  // Starts a new epoch if time_of_day_ns is not the current one's, then stamps the Fix.
  void enterEpoch(std::int64_t time_of_day_ns);
  // Records a date valid at time_of_day_ns (from RMC or ZDA).
  void setDate(const CivilDate& date, std::int64_t time_of_day_ns);
  void updateUtc();
  void markNoFix();
  // A GGA or GNS position with its altitudes (GGA and GNS carry the same fields).
  void takePosition(const Position& position, std::optional<double> alt_msl_m,
                    std::optional<double> geoid_separation_m);
  void markValid();  // a valid position sentence: mode from GSA, else from altitude
  void updateMode();

  FixAccumulatorConfig config_;
  Fix fix_;
  int century_;
  // Last date seen and the time of day it was valid at, to roll the date over at midnight
  // for sentences without a date (GGA, GNS).
  std::optional<CivilDate> date_;
  std::int64_t date_time_of_day_ns_ = 0;
  // Evidence for the mode within the epoch.
  bool epoch_no_fix_ = false;     // the last position sentence said "no fix"
  bool epoch_valid_fix_ = false;  // the last position sentence was a valid fix
  std::optional<int> epoch_gsa_mode_;
};

}  // namespace headingd::nmea
