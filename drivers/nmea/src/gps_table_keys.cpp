#include "headingd/nmea/gps_table_keys.hpp"

#include <sstream>

namespace headingd::nmea {

void readSharedGpsKeys(core::TomlTableReader& r, double& reopen_backoff_initial_s, double& reopen_backoff_max_s,
                       double& epoch_idle_s, std::string_view unknown_keys_hint) {
  reopen_backoff_initial_s = r.number("reopen_backoff_initial_s", reopen_backoff_initial_s, 0.01, 60.0, "s");
  reopen_backoff_max_s = r.number("reopen_backoff_max_s", reopen_backoff_max_s, 0.01, 600.0, "s");
  epoch_idle_s = r.number("epoch_idle_s", epoch_idle_s, 0.0, 10.0, "s");
  r.rejectUnknownKeys(unknown_keys_hint);
  if (reopen_backoff_max_s < reopen_backoff_initial_s) {
    std::ostringstream o;
    o << reopen_backoff_max_s << " is below reopen_backoff_initial_s (" << reopen_backoff_initial_s
      << "), expected max >= initial";
    r.fail("reopen_backoff_max_s", o.str());
  }
}

}  // namespace headingd::nmea
