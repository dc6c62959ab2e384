#include "headingd/gpsd/gpsd_epoch_merger.hpp"

namespace headingd::gpsd {
namespace {

template <class T>
void takeIfSet(std::optional<T>& into, const std::optional<T>& from) {
  if (from) into = from;
}

// Every field of nmea::Fix: the later report's value where it has one.
void mergeInto(nmea::Fix& into, const nmea::Fix& from) {
  takeIfSet(into.time_of_day_ns, from.time_of_day_ns);
  takeIfSet(into.utc_ns, from.utc_ns);
  takeIfSet(into.position, from.position);
  takeIfSet(into.alt_msl_m, from.alt_msl_m);
  takeIfSet(into.geoid_separation_m, from.geoid_separation_m);
  takeIfSet(into.course_deg, from.course_deg);
  takeIfSet(into.speed_mps, from.speed_mps);
  takeIfSet(into.mode, from.mode);
  takeIfSet(into.quality, from.quality);
  takeIfSet(into.hdop, from.hdop);
  takeIfSet(into.pdop, from.pdop);
  takeIfSet(into.vdop, from.vdop);
  takeIfSet(into.satellites_used, from.satellites_used);
  takeIfSet(into.magvar_deg, from.magvar_deg);
  takeIfSet(into.heading_deg, from.heading_deg);
  takeIfSet(into.lat_sigma_m, from.lat_sigma_m);
  takeIfSet(into.lon_sigma_m, from.lon_sigma_m);
  takeIfSet(into.alt_sigma_m, from.alt_sigma_m);
}

void applySky(nmea::Fix& fix, const SkyReport& sky) {
  takeIfSet(fix.hdop, sky.hdop);
  takeIfSet(fix.pdop, sky.pdop);
  takeIfSet(fix.vdop, sky.vdop);
  takeIfSet(fix.satellites_used, sky.satellites_used);
}

}  // namespace

void GpsdEpochMerger::addTpv(const nmea::Fix& fix, std::int64_t receive_ns) {
  const bool new_time = fix.utc_ns && pending_ && pending_->utc_ns && *pending_->utc_ns != *fix.utc_ns;
  if (new_time) completeEpoch();
  if (!pending_ && fix.utc_ns && delivered_utc_ns_ == fix.utc_ns) {
    ++late_reports_;
    return;
  }
  if (!pending_) {
    pending_ = fix;
    applySky(*pending_, sky_between_);
    sky_between_ = {};
  } else {
    mergeInto(*pending_, fix);
  }
  pending_receive_ns_ = receive_ns;
}

void GpsdEpochMerger::addSky(const SkyReport& sky) {
  if (pending_) {
    applySky(*pending_, sky);
  } else {
    sky_between_ = sky;
  }
}

void GpsdEpochMerger::completeEpoch() {
  if (!pending_) return;
  ++epochs_;
  delivered_utc_ns_ = pending_->utc_ns;
  const nmea::Fix fix = *pending_;
  pending_.reset();
  if (on_epoch_) on_epoch_(fix, pending_receive_ns_);
}

}  // namespace headingd::gpsd
