#pragma once
// One line of gpsd's JSON protocol (https://gpsd.io/gpsd_json.html) read into what the GPS
// path uses: a TPV report (time-position-velocity) as an nmea::Fix, the DOPs of a SKY report,
// any other class by name, or what was wrong with the line.
//
// The JSON protocol, not libgps: the protocol is documented and stable across gpsd releases
// (proto_major 3 since 2011), whereas libgps ties the daemon to one libgps ABI (the soname
// changes with gpsd versions) and to its blocking gps_read()/gps_waiting() API, which does not
// fit the daemon's Boost.Asio sources. nlohmann/json (Debian nlohmann-json3-dev, header-only)
// parses each line without exceptions.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "headingd/nmea/fix.hpp"

namespace headingd::gpsd {

// A TPV report. `missing` names the fields a report of its mode should have and did not
// ("" if none): mode, or lat/lon with a 2D/3D fix. The fix is kept either way (without a
// position it is not fix_ok downstream).
struct TpvReport {
  nmea::Fix fix;
  std::string missing;
};

// The DOPs and satellites used of a SKY report (gpsd puts them there, not in TPV).
struct SkyReport {
  std::optional<double> hdop, pdop, vdop;
  std::optional<int> satellites_used;
};

// Another class (VERSION, DEVICES, WATCH, DEVICE, ERROR, ...), by its name.
struct OtherReport {
  std::string class_name;
};

// Not JSON, not an object, no "class", or a field of the wrong type or value (a time that
// is not ISO 8601, a latitude beyond ±90°).
struct MalformedReport {
  std::string why;
};

using GpsdReport = std::variant<TpvReport, SkyReport, OtherReport, MalformedReport>;

GpsdReport parseGpsdReport(std::string_view line);

// "2026-06-01T12:00:13.000Z" as ns since 1970 UTC; nullopt if it is not that form.
std::optional<std::int64_t> parseIsoUtcNs(std::string_view text);

}  // namespace headingd::gpsd
