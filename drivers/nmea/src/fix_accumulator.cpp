#include "headingd/nmea/fix_accumulator.hpp"

#include <chrono>
#include <cstdlib>
#include <type_traits>
#include <variant>

namespace headingd::nmea {
namespace {

constexpr std::int64_t kNsPerDay = 86'400'000'000'000LL;
constexpr std::int64_t kHalfDayNs = kNsPerDay / 2;

std::optional<std::int64_t> daysSinceEpoch(int year, int month, int day) {
  const std::chrono::year_month_day ymd{std::chrono::year{year}, std::chrono::month{static_cast<unsigned>(month)},
                                        std::chrono::day{static_cast<unsigned>(day)}};
  if (!ymd.ok()) return std::nullopt;  // 31 June and the like
  return std::chrono::sys_days{ymd}.time_since_epoch().count();
}

}  // namespace

const char* fixModeName(FixMode m) {
  switch (m) {
    case FixMode::kNoFix: return "no_fix";
    case FixMode::k2D: return "2d";
    case FixMode::k3D: return "3d";
  }
  return "?";
}

FixAccumulator::FixAccumulator(FixAccumulatorConfig config) : config_(config), century_(config.default_century) {}

void FixAccumulator::apply(const DecodedSentence& s) {
  std::visit(
      [this](const auto& data) {
        using T = std::decay_t<decltype(data)>;
        if constexpr (std::is_same_v<T, Gga>) applyGga(data);
        if constexpr (std::is_same_v<T, Rmc>) applyRmc(data);
        if constexpr (std::is_same_v<T, Vtg>) applyVtg(data);
        if constexpr (std::is_same_v<T, Gns>) applyGns(data);
        if constexpr (std::is_same_v<T, Gsa>) applyGsa(data);
        if constexpr (std::is_same_v<T, Gst>) applyGst(data);
        if constexpr (std::is_same_v<T, Hdt>) applyHdt(data);
        if constexpr (std::is_same_v<T, Zda>) applyZda(data);
        if constexpr (std::is_same_v<T, Gll>) applyGll(data);
      },
      s.data);
}

void FixAccumulator::enterEpoch(std::int64_t time_of_day_ns) {
  if (!fix_.time_of_day_ns || std::llabs(time_of_day_ns - *fix_.time_of_day_ns) > config_.same_epoch_tolerance_ns) {
    fix_ = Fix{};
    epoch_no_fix_ = false;
    epoch_valid_fix_ = false;
    epoch_gsa_mode_.reset();
  }
  fix_.time_of_day_ns = time_of_day_ns;
  updateUtc();
}

void FixAccumulator::setDate(const CivilDate& date, std::int64_t time_of_day_ns) {
  if (!daysSinceEpoch(date.year, date.month, date.day)) return;
  date_ = date;
  date_time_of_day_ns_ = time_of_day_ns;
  updateUtc();
}

void FixAccumulator::updateUtc() {
  fix_.utc_ns.reset();
  if (!fix_.time_of_day_ns || !date_) return;
  auto days = daysSinceEpoch(date_->year, date_->month, date_->day);
  if (!days) return;
  // GGA and GNS carry no date: the one from the last RMC/ZDA holds until the time of day
  // jumps back by more than half a day, which is midnight passing.
  const std::int64_t tod = *fix_.time_of_day_ns;
  if (tod < date_time_of_day_ns_ - kHalfDayNs) {
    ++*days;
  } else if (tod > date_time_of_day_ns_ + kHalfDayNs) {
    --*days;  // a late sentence from before the midnight the date was read after
  }
  fix_.utc_ns = *days * kNsPerDay + tod;
  // Follow the epochs so that each midnight is crossed once.
  const std::chrono::sys_days sd{std::chrono::days{*days}};
  const std::chrono::year_month_day ymd{sd};
  date_ = CivilDate{static_cast<int>(ymd.year()), static_cast<int>(static_cast<unsigned>(ymd.month())),
                    static_cast<int>(static_cast<unsigned>(ymd.day()))};
  date_time_of_day_ns_ = tod;
}

void FixAccumulator::markNoFix() {
  epoch_no_fix_ = true;
  epoch_valid_fix_ = false;
  fix_.position.reset();
  fix_.alt_msl_m.reset();
  fix_.geoid_separation_m.reset();
  fix_.course_deg.reset();
  fix_.speed_mps.reset();
  updateMode();
}

void FixAccumulator::markValid() {
  epoch_no_fix_ = false;
  epoch_valid_fix_ = true;
  updateMode();
}

void FixAccumulator::updateMode() {
  if (epoch_no_fix_) {
    fix_.mode = FixMode::kNoFix;
  } else if (epoch_gsa_mode_) {
    // GSA is the receiver's own statement of 2D/3D.
    fix_.mode = *epoch_gsa_mode_ == 3 ? FixMode::k3D : *epoch_gsa_mode_ == 2 ? FixMode::k2D : FixMode::kNoFix;
  } else if (epoch_valid_fix_ && fix_.position) {
    fix_.mode = fix_.alt_msl_m ? FixMode::k3D : FixMode::k2D;
  } else {
    fix_.mode.reset();
  }
}

void FixAccumulator::takePosition(const Position& position, std::optional<double> alt_msl_m,
                                  std::optional<double> geoid_separation_m) {
  fix_.position = position;
  if (alt_msl_m) fix_.alt_msl_m = alt_msl_m;
  if (geoid_separation_m) fix_.geoid_separation_m = geoid_separation_m;
  markValid();
}

void FixAccumulator::applyGga(const Gga& g) {
  if (g.time_of_day_ns) enterEpoch(*g.time_of_day_ns);
  fix_.quality = g.quality;
  if (g.satellites_used) fix_.satellites_used = g.satellites_used;
  if (g.hdop) fix_.hdop = g.hdop;
  // Quality 0 is "fix not available"; a missing quality is no evidence of a fix either.
  if (!g.position || !g.quality || *g.quality == 0) {
    markNoFix();
    return;
  }
  takePosition(*g.position, g.alt_msl_m, g.geoid_separation_m);
}

void FixAccumulator::applyRmc(const Rmc& r) {
  const bool valid = r.status == 'A' && (!r.mode_indicator || modeIndicatorIsValid(*r.mode_indicator));
  if (r.time_of_day_ns) enterEpoch(*r.time_of_day_ns);
  if (!valid || !r.position) {
    // Some receivers send stale or made-up dates with status V, so the date is not used.
    markNoFix();
    return;
  }
  if (r.date && r.time_of_day_ns) setDate({century_ + r.date->yy, r.date->month, r.date->day}, *r.time_of_day_ns);
  fix_.position = r.position;
  if (r.speed_mps) fix_.speed_mps = r.speed_mps;
  if (r.course_deg) fix_.course_deg = r.course_deg;
  if (r.magvar_deg) fix_.magvar_deg = r.magvar_deg;
  markValid();
}

void FixAccumulator::applyVtg(const Vtg& v) {
  // Mode N is "data not valid"; and in an epoch the receiver called fix-less the course
  // and speed mean nothing, whatever VTG says.
  if ((v.mode_indicator && !modeIndicatorIsValid(*v.mode_indicator)) || epoch_no_fix_) return;
  if (v.course_deg) fix_.course_deg = v.course_deg;
  if (v.speed_mps) fix_.speed_mps = v.speed_mps;
}

void FixAccumulator::applyGns(const Gns& g) {
  if (g.time_of_day_ns) enterEpoch(*g.time_of_day_ns);
  // One mode letter per constellation: a fix if any constellation has one.
  bool any_valid = false;
  for (const char m : g.mode_indicators) any_valid = any_valid || (m != '\0' && modeIndicatorIsValid(m));
  if (g.satellites_used) fix_.satellites_used = g.satellites_used;
  if (g.hdop) fix_.hdop = g.hdop;
  if (g.nav_status == 'V') return;
  if (!any_valid || !g.position) {
    markNoFix();
    return;
  }
  takePosition(*g.position, g.alt_msl_m, g.geoid_separation_m);
}

void FixAccumulator::applyGll(const Gll& g) {
  const bool valid = g.status == 'A' && (!g.mode_indicator || modeIndicatorIsValid(*g.mode_indicator));
  if (g.time_of_day_ns) enterEpoch(*g.time_of_day_ns);
  if (!valid || !g.position) {
    markNoFix();
    return;
  }
  fix_.position = g.position;
  markValid();
}

void FixAccumulator::applyGsa(const Gsa& g) {
  if (g.fix_mode) epoch_gsa_mode_ = g.fix_mode;
  if (g.pdop) fix_.pdop = g.pdop;
  if (g.hdop) fix_.hdop = g.hdop;
  if (g.vdop) fix_.vdop = g.vdop;
  updateMode();
}

void FixAccumulator::applyGst(const Gst& g) {
  // GST's time is that of the fix it describes, often the previous one, so it does not
  // start an epoch.
  if (g.lat_sigma_m) fix_.lat_sigma_m = g.lat_sigma_m;
  if (g.lon_sigma_m) fix_.lon_sigma_m = g.lon_sigma_m;
  if (g.alt_sigma_m) fix_.alt_sigma_m = g.alt_sigma_m;
}

void FixAccumulator::applyHdt(const Hdt& h) {
  if (h.heading_deg) fix_.heading_deg = h.heading_deg;
}

void FixAccumulator::applyZda(const Zda& z) {
  if (!z.time_of_day_ns) return;
  enterEpoch(*z.time_of_day_ns);
  if (z.year && z.month && z.day) {
    century_ = *z.year - *z.year % 100;
    setDate({*z.year, *z.month, *z.day}, *z.time_of_day_ns);
  }
}

}  // namespace headingd::nmea
