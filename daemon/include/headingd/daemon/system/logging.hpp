#pragma once
// spdlog set-up: stderr always (journald picks it up under systemd), plus an optional file
// that SIGHUP reopens (for logrotate). When stderr is the journal (JOURNAL_STREAM names it,
// journal_stream.hpp) lines carry their priority as an sd-daemon "<N>" prefix and no
// timestamp of their own (the journal adds one): "<4>[warning] gps: ...".
#include <spdlog/spdlog.h>
#include <cstdint>
#include <memory>
#include <string>

#include "headingd/daemon/config/config.hpp"

namespace headingd::daemon {

// Makes the default logger; level "" keeps the configured one. Throws spdlog::spdlog_ex
// when the log file cannot be opened.
void setUpLogging(const LogConfig& config, const std::string& level_override);
// Closes and reopens the log file (if one is configured). Safe while other threads log. If
// it cannot be opened, logging goes on to stderr alone (counted, and logged as an error).
void reopenLogFile();
// Failed writes, flushes and reopens of the log file since start (a full disk): STATUS
// counter log_write_errors. The daemon runs on; stderr still gets every line.
std::uint64_t logWriteErrors();

}  // namespace headingd::daemon
