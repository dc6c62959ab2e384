#pragma once
// The keys of the [gps] table that every GPS source reads alike (source = "serial" and
// source = "gpsd"; config/gps.toml documents them): the reopen back-off and the quiet that
// ends an epoch. Read once here so that both sources take the same ranges and say the same
// thing about a bad value.
#include <string_view>

#include "headingd/core/toml_table_reader.hpp"

namespace headingd::nmea {

// Reads reopen_backoff_initial_s, reopen_backoff_max_s and epoch_idle_s into the fields given
// (they hold the defaults), then ends the table: rejects the keys nobody read (`hint` ends that
// message) and checks max >= initial. Call it after the source's own keys. Throws
// core::ConfigError.
void readSharedGpsKeys(core::TomlTableReader& r, double& reopen_backoff_initial_s, double& reopen_backoff_max_s,
                       double& epoch_idle_s, std::string_view unknown_keys_hint);

}  // namespace headingd::nmea
