// headingd-nmea-dump: runs a capture file through the NMEA parser and prints, as JSON lines,
// the fix after every decoded sentence, then every counter.
//
// '#' comment lines (gpsd's capture files carry them; they were never on the wire) are
// stripped here, before the parser, and counted as "comment_lines"; --keep-comments feeds
// them to the parser like any other bytes.
#include <unistd.h>
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "headingd/cli/parse_command_line.hpp"
#include "headingd/files/input_file.hpp"
#include "headingd/nmea/comment_filter.hpp"
#include "headingd/nmea/parser.hpp"

namespace {

using headingd::nmea::Fix;
using headingd::nmea::FixUpdate;

// 2020-03-18T13:28:20.600Z
std::string isoUtc(std::int64_t utc_ns) {
  constexpr std::int64_t kNsPerDay = 86'400'000'000'000LL;
  std::int64_t days = utc_ns / kNsPerDay;
  std::int64_t tod = utc_ns % kNsPerDay;
  if (tod < 0) {
    tod += kNsPerDay;
    --days;
  }
  const std::chrono::year_month_day ymd{std::chrono::sys_days{std::chrono::days{days}}};
  const std::int64_t ms = tod / 1'000'000;
  char buf[40];
  std::snprintf(buf, sizeof buf, "%04d-%02u-%02uT%02" PRId64 ":%02" PRId64 ":%02" PRId64 ".%03" PRId64 "Z",
                static_cast<int>(ymd.year()), static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()),
                ms / 3'600'000, ms / 60'000 % 60, ms / 1000 % 60, ms % 1000);
  return buf;
}

void printUpdate(const FixUpdate& u) {
  const Fix& f = u.fix;
  std::printf("{\"sentence\":\"%s%s\"", headingd::nmea::talkerName(u.talker), headingd::nmea::sentenceTypeName(u.type));
  if (f.utc_ns) std::printf(",\"utc\":\"%s\"", isoUtc(*f.utc_ns).c_str());
  if (f.position) std::printf(",\"lat\":%.9f,\"lon\":%.9f", f.position->lat_deg, f.position->lon_deg);
  if (f.alt_msl_m) std::printf(",\"alt_m\":%.3f", *f.alt_msl_m);
  if (f.geoid_separation_m) std::printf(",\"geoid_sep_m\":%.3f", *f.geoid_separation_m);
  if (f.course_deg) std::printf(",\"course_deg\":%.4f", *f.course_deg);
  if (f.speed_mps) std::printf(",\"speed_mps\":%.4f", *f.speed_mps);
  if (f.mode) std::printf(",\"mode\":\"%s\"", headingd::nmea::fixModeName(*f.mode));
  if (f.quality) std::printf(",\"quality\":%d", *f.quality);
  if (f.hdop) std::printf(",\"hdop\":%.2f", *f.hdop);
  if (f.satellites_used) std::printf(",\"sats\":%d", *f.satellites_used);
  if (f.magvar_deg) std::printf(",\"magvar_deg\":%.4f", *f.magvar_deg);
  if (f.heading_deg) std::printf(",\"heading_deg\":%.3f", *f.heading_deg);
  std::printf("}\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Parse an NMEA 0183 capture; print the fix after every decoded sentence and the counters, as JSON lines."};
  std::string path;
  bool keep_comments = false;
  std::size_t max_line = headingd::nmea::FramerConfig{}.max_line_length;
  app.add_option("FILE", path, "capture file (raw serial bytes; gpsd-style '#' comment lines are stripped)")
      ->required();
  app.add_flag("--keep-comments", keep_comments, "feed '#' lines to the parser instead of stripping them");
  app.add_option("--max-line", max_line, "longest line accepted, '$' through checksum")->check(CLI::Range(4, 4096));
  app.footer(
      std::string("Exit codes: 0 the whole file was parsed (what the parser could not use is in the counters), 1 FILE "
                  "cannot be read (missing, a directory, a FIFO or a device), 2 bad arguments.") +
      "\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;

  // A regular file only: a directory, a FIFO or a device is refused (input_file.hpp); the
  // capture is read in chunks, so its length does not matter.
  std::optional<headingd::files::InputFile> in;
  try {
    in.emplace(path);
  } catch (const headingd::files::FileError& e) {
    std::fprintf(stderr, "headingd-nmea-dump: %s\n", e.what());
    return 1;
  }
  headingd::nmea::ParserConfig config;
  config.framer.max_line_length = max_line;
  headingd::nmea::Parser parser(config);
  headingd::nmea::CommentFilter comments;
  std::vector<std::uint8_t> chunk(4096), filtered;
  std::vector<FixUpdate> updates;
  while (true) {
    const ssize_t got = ::read(in->fd(), chunk.data(), chunk.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      std::fprintf(stderr, "headingd-nmea-dump: %s: read error: %s\n", path.c_str(), std::strerror(errno));
      return 1;
    }
    const auto n = static_cast<std::size_t>(got);
    if (n == 0) break;
    const std::span<const std::uint8_t> bytes(chunk.data(), n);
    updates.clear();
    if (keep_comments) {
      parser.feed(bytes, updates);
    } else {
      filtered.clear();
      comments.filter(bytes, filtered);
      parser.feed(filtered, updates);
    }
    for (const auto& u : updates) printUpdate(u);
  }
  parser.finish();

  std::printf("{\"counters\":{\"comment_lines\":%" PRIu64, comments.commentLines());
  headingd::nmea::forEachCounter(
      parser.counters(), [](const char* name, std::uint64_t value) { std::printf(",\"%s\":%" PRIu64, name, value); });
  std::printf("}}\n");
  return 0;
}
