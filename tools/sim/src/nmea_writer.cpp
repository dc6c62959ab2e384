#include "headingd/sim/nmea_writer.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace headingd::sim {

namespace {

std::string format(const char* fmt, auto... args) {
  char buf[128];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

// ddmm.mmmmm / dddmm.mmmmm and the hemisphere letter. Rounded once, in integer units of
// 1e-5 minute, so 59.99999... never prints as "60.00000" minutes.
std::string angle(double deg, int degree_digits, char positive, char negative) {
  const long long units = std::llround(std::abs(deg) * 60.0 * 1e5);
  const long long whole_deg = units / 6000000;
  const long long minute_units = units % 6000000;
  return format("%0*lld%02lld.%05lld,%c", degree_digits, whole_deg, minute_units / 100000, minute_units % 100000,
                deg < 0.0 ? negative : positive);
}

// An angle in [0, 360) to 0.01°, wrapped after rounding so that 359.996 reads "0.00".
std::string degrees360(double deg) {
  long long centi = std::llround(deg * 100.0) % 36000;
  if (centi < 0) centi += 36000;
  return format("%lld.%02lld", centi / 100, centi % 100);
}

constexpr double kKnotsPerMps = 3600.0 / 1852.0;

}  // namespace

UtcStamp utcAt(const UtcClock& clock, double t_s) {
  const long long centis = std::llround((clock.time_of_day_s + t_s) * 100.0);
  const long long day_offset = centis / 8640000;
  const long long cs_of_day = centis % 8640000;
  using namespace std::chrono;
  const year_month_day date{
      sys_days{year{clock.year} / month{static_cast<unsigned>(clock.month)} / static_cast<unsigned>(clock.day)} +
      days{day_offset}};
  UtcStamp s;
  s.hhmmss = format("%02lld%02lld%02lld.%02lld", cs_of_day / 360000, cs_of_day / 6000 % 60, cs_of_day / 100 % 60,
                    cs_of_day % 100);
  s.ddmmyy = format("%02u%02u%02d", static_cast<unsigned>(date.day()), static_cast<unsigned>(date.month()),
                    static_cast<int>(date.year()) % 100);
  return s;
}

std::uint8_t nmeaChecksum(std::string_view body) {
  std::uint8_t x = 0;
  for (const char c : body) x ^= static_cast<std::uint8_t>(c);
  return x;
}

std::string nmeaSentence(std::string_view body) {
  return "$" + std::string(body) + format("*%02X\r\n", static_cast<unsigned>(nmeaChecksum(body)));
}

std::string nmeaEpoch(const GpsEpoch& e, const NmeaContext& c) {
  const UtcStamp utc = utcAt(c.clock, e.t_s);
  const std::string& tk = c.talker;
  if (!e.fix) {
    // No fix: time and date are still known (the receiver's clock runs on), positions empty,
    // GGA quality 0, RMC status V, mode indicator N.
    return nmeaSentence(tk + "GGA," + utc.hhmmss + ",,,,,0,00,99.99,,M,,M,,") +
           nmeaSentence(tk + "RMC," + utc.hhmmss + ",V,,,,,,," + utc.ddmmyy + ",,,N") +
           nmeaSentence(tk + "VTG,,T,,M,,N,,K,N");
  }
  const std::string lat = angle(e.position.latitude_deg, 2, 'N', 'S');
  const std::string lon = angle(e.position.longitude_deg, 3, 'E', 'W');
  // Geoid separation is not modelled: altitude is above the ellipsoid and N is written as 0.
  const std::string gga = tk + "GGA," + utc.hhmmss + "," + lat + "," + lon + ",1," + format("%02d", e.satellites) +
                          "," + format("%.2f", e.hdop) + "," + format("%.1f", e.position.height_m) + ",M,0.0,M,,";
  const std::string knots = format("%.3f", e.speed_mps * kKnotsPerMps);
  const std::string course = e.course_deg ? degrees360(*e.course_deg) : "";
  const double var = c.magnetic_variation_deg;
  const std::string variation = format("%.1f,%c", std::abs(var), var < 0.0 ? 'W' : 'E');
  const std::string rmc = tk + "RMC," + utc.hhmmss + ",A," + lat + "," + lon + "," + knots + "," + course + "," +
                          utc.ddmmyy + "," + variation + ",A";
  const std::string magnetic_course = e.course_deg ? degrees360(*e.course_deg - var) : "";
  const std::string vtg = tk + "VTG," + course + ",T," + magnetic_course + ",M," + knots + ",N," +
                          format("%.3f", e.speed_mps * 3.6) + ",K,A";
  return nmeaSentence(gga) + nmeaSentence(rmc) + nmeaSentence(vtg);
}

}  // namespace headingd::sim
