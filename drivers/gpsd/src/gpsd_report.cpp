#include "headingd/gpsd/gpsd_report.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace headingd::gpsd {
namespace {

using nlohmann::json;

constexpr std::int64_t kNsPerDay = 86'400'000'000'000;

// A field's number, nullopt if absent; throws-free: a present non-number sets *bad.
std::optional<double> number(const json& object, const char* key, std::string* bad) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return std::nullopt;
  if (!it->is_number()) {
    if (bad->empty()) *bad = std::string("\"") + key + "\" is not a number";
    return std::nullopt;
  }
  const double v = it->get<double>();
  if (!std::isfinite(v)) {
    if (bad->empty()) *bad = std::string("\"") + key + "\" is not finite";
    return std::nullopt;
  }
  return v;
}

std::optional<nmea::FixMode> fixModeOf(double mode) {
  // TPV mode: 0 unknown, 1 no fix, 2 2D, 3 3D.
  if (mode == 0.0 || mode == 1.0) return nmea::FixMode::kNoFix;
  if (mode == 2.0) return nmea::FixMode::k2D;
  if (mode == 3.0) return nmea::FixMode::k3D;
  return std::nullopt;
}

GpsdReport parseTpv(const json& o) {
  TpvReport r;
  std::string bad;
  nmea::Fix& f = r.fix;
  const auto mode = number(o, "mode", &bad);
  const auto lat = number(o, "lat", &bad);
  const auto lon = number(o, "lon", &bad);
  const auto alt_msl = number(o, "altMSL", &bad);
  const auto alt_old = number(o, "alt", &bad);  // before gpsd 3.20: MSL; since, the same as altMSL
  const auto alt_hae = number(o, "altHAE", &bad);
  const auto geoid_sep = number(o, "geoidSep", &bad);
  const auto track = number(o, "track", &bad);
  const auto speed = number(o, "speed", &bad);
  const auto magvar = number(o, "magvar", &bad);
  if (!bad.empty()) return MalformedReport{"TPV: " + bad};
  if (const auto it = o.find("time"); it != o.end()) {
    const auto utc = it->is_string() ? parseIsoUtcNs(it->get_ref<const std::string&>()) : std::nullopt;
    if (!utc) return MalformedReport{"TPV: \"time\" is not an ISO 8601 UTC time"};
    f.utc_ns = *utc;
    f.time_of_day_ns = ((*utc % kNsPerDay) + kNsPerDay) % kNsPerDay;
  }
  if (mode) {
    f.mode = fixModeOf(*mode);
    if (!f.mode) return MalformedReport{"TPV: \"mode\" is not 0, 1, 2 or 3"};
  } else {
    r.missing = "mode";
  }
  if (lat && lon) {
    if (std::abs(*lat) > 90.0 || std::abs(*lon) > 180.0) return MalformedReport{"TPV: lat/lon out of range"};
    f.position = nmea::Position{*lat, *lon};
  } else if (f.mode && *f.mode != nmea::FixMode::kNoFix) {
    r.missing = "lat/lon";
  }
  // The height above the ellipsoid is what the estimator uses (MSL + geoid separation).
  if (alt_msl || alt_old) {
    f.alt_msl_m = alt_msl ? alt_msl : alt_old;
    f.geoid_separation_m = geoid_sep;
  } else if (alt_hae) {
    f.geoid_separation_m = geoid_sep.value_or(0.0);
    f.alt_msl_m = *alt_hae - *f.geoid_separation_m;
  }
  if (track) f.course_deg = std::fmod(std::fmod(*track, 360.0) + 360.0, 360.0);
  f.speed_mps = speed;
  f.magvar_deg = magvar;  // east positive, as gpsd sends it
  return r;
}

SkyReport parseSky(const json& o, std::string* bad) {
  SkyReport s;
  s.hdop = number(o, "hdop", bad);
  s.pdop = number(o, "pdop", bad);
  s.vdop = number(o, "vdop", bad);
  if (const auto used = number(o, "uSat", bad)) s.satellites_used = static_cast<int>(*used);
  return s;
}

}  // namespace

std::optional<std::int64_t> parseIsoUtcNs(std::string_view text) {
  // YYYY-MM-DDThh:mm:ss[.fff]Z; gpsd always sends UTC with a Z.
  if (text.size() < 20 || text.size() > 40 || text.back() != 'Z') return std::nullopt;
  const std::string s(text);
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, n = 0;
  double sec = 0.0;
  if (std::sscanf(s.c_str(), "%4d-%2d-%2dT%2d:%2d:%lf%n", &y, &mo, &d, &h, &mi, &sec, &n) != 6) return std::nullopt;
  if (static_cast<std::size_t>(n) != s.size() - 1) return std::nullopt;
  using namespace std::chrono;
  const year_month_day date{year(y), month(static_cast<unsigned>(mo)), day(static_cast<unsigned>(d))};
  // Years past 2200 would overflow int64 nanoseconds (2262); none before 1970 is a GPS time.
  if (y < 1970 || y > 2200) return std::nullopt;
  if (!date.ok() || h < 0 || h > 23 || mi < 0 || mi > 59 || !(sec >= 0.0 && sec < 61.0)) return std::nullopt;
  const std::int64_t days_ns = sys_days(date).time_since_epoch().count() * kNsPerDay;
  return days_ns + (static_cast<std::int64_t>(h) * 3600 + mi * 60) * 1'000'000'000 +
         static_cast<std::int64_t>(std::llround(sec * 1e9));
}

GpsdReport parseGpsdReport(std::string_view line) {
  const json o = json::parse(line.begin(), line.end(), nullptr, /*allow_exceptions=*/false);
  if (o.is_discarded()) return MalformedReport{"not JSON"};
  if (!o.is_object()) return MalformedReport{"not a JSON object"};
  const auto cls = o.find("class");
  if (cls == o.end() || !cls->is_string()) return MalformedReport{"no \"class\""};
  const std::string& name = cls->get_ref<const std::string&>();
  if (name == "TPV") return parseTpv(o);
  if (name == "SKY") {
    std::string bad;
    SkyReport s = parseSky(o, &bad);
    if (!bad.empty()) return MalformedReport{"SKY: " + bad};
    return s;
  }
  return OtherReport{name};
}

}  // namespace headingd::gpsd
