#pragma once
// An LCM log to one CSV table per channel and message type, in two streaming passes: the
// first finds the tables, their columns and the first bad event, the second writes every
// event before it. Memory holds one event and the column names, whatever the log's length.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "headingd/lcm_export/lcm_log_reader.hpp"

namespace headingd::lcm_export {

struct ExportOptions {
  std::filesystem::path log_path;
  std::filesystem::path out_dir;      // created when missing
  std::vector<std::string> channels;  // exact channel names; empty: every channel
};

struct ExportedTable {
  std::string channel;
  std::string type;  // "heading_t"
  std::filesystem::path file;
  std::uint64_t rows = 0;
};

// Messages whose fingerprint is none of headingd's types (or shorter than a fingerprint).
struct UnknownMessages {
  std::string channel;
  std::uint64_t messages = 0;
  std::vector<std::int64_t> fingerprints;  // the first few distinct ones
};

struct ExportResult {
  std::vector<ExportedTable> tables;
  std::vector<UnknownMessages> unknown;
  std::vector<std::string> missing_channels;  // asked for with --channel, not in the log
  std::vector<std::string> log_channels;      // every channel of the log (read part), sorted
  std::uint64_t events_read = 0;              // good events, whatever their channel
  std::optional<LcmLogError> log_error;       // the first bad event: nothing from it on is exported
};

// The file name of a channel's table: bytes other than A-Z a-z 0-9 . _ - become '_', and a
// leading '.' too (no hidden files, no ".."); `type` is added when the channel carries more
// than one of headingd's types: "HEADING.csv", "MIXED.heading_t.csv".
std::string tableFileName(const std::string& channel, const std::string& type, bool several_types);

// A table whose file is the log itself (a log named DIR/HEADING.csv): refused before anything
// is written, as a bad argument.
struct TableOverLogError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws TableOverLogError (above); std::runtime_error when the log cannot be opened or read,
// or a table cannot be written (the tables not yet in place are removed). A bad log is not thrown: its error is
// in the result, after every table holds what came before it.
ExportResult exportLcmLog(const ExportOptions& options);

}  // namespace headingd::lcm_export
