// headingd-lcm-export: an LCM log (lcm-logger) as one CSV table per channel, for pandas,
// PlotJuggler or a spreadsheet.
#include <cinttypes>
#include <cstdio>
#include <exception>

#include "headingd/cli/parse_command_line.hpp"
#include "headingd/lcm_export/log_export.hpp"

namespace {

// Exit status (also in --help).
constexpr int kExitOk = 0;
constexpr int kExitBadLog = 1;
constexpr int kExitUsage = 2;
constexpr int kExitIo = 3;

constexpr const char* kFooter = R"(Tables:
  One CSV per channel, DIR/<channel>.csv (bytes other than A-Z a-z 0-9 . _ - in the
  channel's name become _); a channel that carries several of headingd's types gets
  one table per type, DIR/<channel>.<type>.csv. A header row, one message a row.
  The message type is told by the 8-byte fingerprint at the start of each message, not
  by the channel's name, so channels renamed by the [lcm] *_channel keys export alike.
  Messages of other types are counted per channel and reported on stderr (not an error).

Columns:
  log_utime   the log event's timestamp (lcm-logger's receive time), microseconds since 1970
  event       the log event's number
  then every field of the message in declaration order (daemon/lcm/*.lcm):
  fixed arrays name_0, name_1, ...; 2-D name_0_0, name_0_1, ...; nested structs name.field.
  Variable-length arrays of named elements are keyed by the element's name, so a column
  means the same thing in every row even when sources or counters come and go:
  sources.<source>.state, sources.<source>.counters.<counter>, rings.<ring>.dropped,
  counters.<counter> (a counter_t's value); names are kept as they are, dots included
  (rings.candump_log.imu.dropped). A first pass over the log finds every name;
  a cell is empty where a message has no such element. An element with an empty or
  repeated name is keyed by its index instead: counters.#3.name, counters.#3.value.
  The order of the elements within one message is not kept, their names and values are.
  Integers exact; doubles in the shortest text that reads back to the same double (nan,
  inf, -inf); booleans 0/1; text quoted as RFC 4180 says when it holds , " CR or LF.

Output:
  stdout: one line per table: channel, type, rows, file (tab-separated).
  Each table is written to a temporary file in DIR (.<table>.csv.XXXXXX) and renamed
  into place at the end: a failed or interrupted run (also SIGINT, SIGTERM) never leaves a
  half-written table under its final name, nor the temporary file. Tables of
  earlier exports into DIR are replaced only when this log has the same table.

Exit status:
  0  every event of the log read and exported
  1  bad log: a bad sync word, an absurd channel or data length, an event cut off by
     the end of the file, or a message of headingd's types that does not decode; stderr
     names the file and the byte offset of the bad event; every event before it is
     exported and the tables are in place
  2  bad arguments, a --channel that the log does not have (the others are exported), or
     a table that would be the log itself (nothing is written)
  3  the log cannot be read or a table cannot be written (tables not in place are removed)

Example (record, export, open in pandas):
  lcm-logger --lcm-url='udpm://239.255.76.67:7667?ttl=0' run.lcm

  headingd-lcm-export run.lcm --out-dir run --channel HEADING,STATUS

  python3 -c 'import pandas; print(pandas.read_csv("run/HEADING.csv").describe())')";

}  // namespace

int main(int argc, char** argv) {
  using namespace headingd::lcm_export;
  CLI::App app{"Export an LCM log (as lcm-logger writes it) of headingd's messages to one CSV table per channel."};
  ExportOptions options;
  std::string log_path, out_dir;
  app.add_option("log", log_path, "LCM log file (lcm-logger's format)")->required();
  app.add_option("--out-dir", out_dir, "folder for the tables (created when missing)")->required();
  app.add_option("--channel", options.channels,
                 "export only this channel (exact name; repeat it or give a comma-separated list; default: all)")
      ->delimiter(',');
  app.footer(std::string(kFooter) + "\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;
  options.log_path = log_path;
  options.out_dir = out_dir;

  ExportResult result;
  try {
    result = exportLcmLog(options);
  } catch (const TableOverLogError& e) {
    std::fprintf(stderr, "headingd-lcm-export: %s\n", e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-lcm-export: %s\n", e.what());
    return kExitIo;
  }

  for (const ExportedTable& table : result.tables) {
    std::printf("%s\t%s\t%" PRIu64 " rows\t%s\n", table.channel.c_str(), table.type.c_str(), table.rows,
                table.file.c_str());
  }
  for (const UnknownMessages& u : result.unknown) {
    std::string fingerprints;
    for (const std::int64_t f : u.fingerprints) {
      char text[24];
      std::snprintf(text, sizeof text, " 0x%016" PRIx64, static_cast<std::uint64_t>(f));
      fingerprints += text;
    }
    std::fprintf(stderr, "headingd-lcm-export: %s: %" PRIu64 " messages of unknown type not exported (fingerprint%s)\n",
                 u.channel.c_str(), u.messages,
                 fingerprints.empty() ? " none: shorter than 8 bytes" : fingerprints.c_str());
  }
  if (result.tables.empty() && !result.log_error) {
    std::fprintf(stderr, "headingd-lcm-export: %s: no message of headingd's types%s, no table written\n",
                 log_path.c_str(), options.channels.empty() ? "" : " on the chosen channels");
  }
  int status = kExitOk;
  if (!result.missing_channels.empty()) {
    std::string have;
    for (const std::string& c : result.log_channels) have += (have.empty() ? "" : ", ") + c;
    for (const std::string& c : result.missing_channels) {
      std::fprintf(stderr, "headingd-lcm-export: %s: no channel %s in the log (it has: %s)\n", log_path.c_str(),
                   c.c_str(), have.empty() ? "none" : have.c_str());
    }
    status = kExitUsage;
  }
  if (result.log_error) {
    std::fprintf(stderr,
                 "headingd-lcm-export: %s: byte %" PRIu64 ": %s; the %" PRIu64 " events before it are exported\n",
                 log_path.c_str(), result.log_error->offset(), result.log_error->what(), result.events_read);
    status = kExitBadLog;
  }
  return status;
}
