// The parser against gpsd, over gpsd's own regression corpus: ../shared/data/gpsd-logs (about
// 100 captures) when it is beside the checkout, else the repository's tests/data/gpsd-logs
// (11); README.md there. Every .log goes through the parser, binary ones included: no crash, no hang,
// bounded buffer, same result whatever the chunking. For every .log with a .log.chk, each
// gpsd TPV report that directly follows a GGA, RMC or GNS sentence is compared with our Fix
// after that same sentence: lat/lon within 1e-7 deg, track within 0.01 deg, speed within
// 0.01 m/s, on the fields both sides have.
//
// What gpsd reports, and so what is compared (gpsd's libgpsd_core.c, driver_nmea0183.c):
// - gpsd clears its fix when a sentence with a new UTC time of day starts a reporting cycle,
//   as our FixAccumulator does, so neither side carries a course or speed into the next
//   second;
// - gpsd prints lat/lon/track/speed only with mode >= 2D;
// - gpsd fills a missing speed with one derived from successive positions, and a missing
//   altitude/magvar from its own models; we report only what the receiver sent, so those
//   fields have nothing to be compared with;
// - gpsd keeps a position from GGA quality 0 or RMC mode N; we drop it (not a fix), so
//   again nothing to compare;
// - gpsd calls a GPGGA/GNGGA with fewer than 3 satellites used "no fix" and prints no
//   position; we follow the quality flag (furuno_gl_ga.log sends 00 satellites with a DGPS
//   fix while its GNS of the same second counts 11), so such positions are ours only.
// The capture files' '#' comment lines are stripped with CommentFilter before the parser.
// The table also counts, per field, reports where only gpsd has a value (its derived speed;
// a GGA quality-0 position) and where only we have a position (gpsd said mode 1).
// NMEA_CORPUS_DEBUG=1 in the environment prints each report where only one side has a field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "headingd/nmea/comment_filter.hpp"
#include "headingd/nmea/parser.hpp"
#include "test_data.hpp"

namespace {

using headingd::nmea::FixUpdate;
using headingd::nmea::Parser;

using headingd::test_data::kGpsdLogs;
const std::filesystem::path kLogsDir{kGpsdLogs.dir};
constexpr double kLatLonTolDeg = 1e-7;
constexpr double kTrackTolDeg = 0.01;
constexpr double kSpeedTolMps = 0.01;

// A disagreement that is gpsd's own quirk, not ours to copy: keyed by file, the exact
// sentence the TPV follows, and the field. Each one must still occur (stale entries fail).
struct KnownDifference {
  const char* file;
  const char* sentence;
  const char* field;  // "lat/lon", "track", "speed"
  const char* why;
};

// Empty: every report compared agrees. Add entries here, with the reason, rather than
// widening a tolerance or skipping a file.
const std::vector<KnownDifference> kKnownDifferences = {};

std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Called before main to name the parameterised tests, so it prints nothing; each test
// announces the set it reads (test_data::announce).
std::vector<std::string> logFiles() {
  std::vector<std::string> names;
  for (const auto& p : headingd::test_data::files(kGpsdLogs)) names.push_back(p.filename().string());
  return names;
}

std::vector<std::string> logFilesWithChk() {
  std::vector<std::string> names;
  for (const auto& n : logFiles()) {
    if (std::filesystem::exists(kLogsDir / (n + ".chk"))) names.push_back(n);
  }
  return names;
}

std::string testName(const std::string& file) {
  std::string n;
  for (const char c : file) n += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return n;
}

std::optional<double> jsonNumber(const std::string& json, const char* key) {
  const std::string k = std::string("\"") + key + "\":";
  const auto at = json.find(k);
  if (at == std::string::npos) return std::nullopt;
  return std::strtod(json.c_str() + at + k.size(), nullptr);
}

struct ParseRun {
  std::vector<FixUpdate> updates;
  headingd::nmea::Counters counters;
  std::uint64_t comment_lines = 0;
  std::size_t max_buffered = 0;
};

// Feeds the file in chunks of random size (deterministic seed), as a serial port would.
ParseRun parseLog(const std::string& bytes, unsigned seed, std::size_t max_chunk) {
  ParseRun run;
  Parser parser;
  headingd::nmea::CommentFilter comments;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> chunk(1, max_chunk);
  std::vector<std::uint8_t> filtered;
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t n = std::min(chunk(rng), bytes.size() - at);
    filtered.clear();
    comments.filter(std::span(data + at, n), filtered);
    parser.feed(filtered, run.updates);
    run.max_buffered = std::max(run.max_buffered, parser.buffered());
    at += n;
  }
  parser.finish();
  run.counters = parser.counters();
  run.comment_lines = comments.commentLines();
  return run;
}

// Which gpsd reports to check: those after GGA/RMC/GNS (the agreement asked for), or, as a
// wider net, those after any sentence we decode (VTG, GLL, ZDA, GSA, GST, HDT too).
enum class Scope { kFixSentences, kAllDecoded };

bool inScope(const std::string& line, Scope scope) {
  const auto d = headingd::nmea::decodeSentence(line);
  if (d.status != headingd::nmea::DecodeStatus::kDecoded) {
    // A fix sentence we could not decode is still one to account for.
    if (scope == Scope::kAllDecoded || line.size() < 7 || line[0] != '$') return false;
    const std::string type = line.substr(3, 3);
    return type == "GGA" || type == "RMC" || type == "GNS";
  }
  using headingd::nmea::SentenceType;
  return scope == Scope::kAllDecoded || d.sentence->type == SentenceType::kGGA ||
         d.sentence->type == SentenceType::kRMC || d.sentence->type == SentenceType::kGNS;
}

struct FileResult {
  std::string file;
  bool has_chk = false;
  std::size_t tpv_after_fix = 0;   // gpsd TPVs following an in-scope sentence in the .chk
  std::size_t gpsd_generated = 0;  // ... whose sentence gpsd made up from binary (not input)
  std::size_t not_decoded = 0;     // ... whose sentence is input we did not decode
  std::size_t compared = 0;        // TPVs with at least one field both sides have
  std::size_t agreed = 0;
  std::size_t known = 0;                         // disagreements explained by kKnownDifferences
  std::size_t latlon = 0, track = 0, speed = 0;  // field comparisons made
  std::size_t gpsd_only_latlon = 0, gpsd_only_track = 0, gpsd_only_speed = 0;
  std::size_t ours_only_latlon = 0;
  std::vector<std::string> disagreements;
  std::set<std::size_t> known_used;
};

FileResult checkFile(const std::string& name, Scope scope = Scope::kFixSentences) {
  FileResult r;
  r.file = name;
  const std::string log = readFile(kLogsDir / name);
  const ParseRun run = parseLog(log, 20240601u, 4096);
  const auto chk_path = kLogsDir / (name + ".chk");
  if (!std::filesystem::exists(chk_path)) return r;
  r.has_chk = true;

  std::istringstream chk(readFile(chk_path));
  std::string line;
  std::size_t cursor = 0;            // next of our updates to match
  const FixUpdate* state = nullptr;  // our update for the last fix sentence in the .chk
  std::string last_sentence;
  enum class Match { kNone, kOurs, kGenerated, kNotDecoded } match = Match::kNone;
  while (std::getline(chk, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '$' || line[0] == '!') {
      last_sentence = line;
      match = Match::kNone;
      state = nullptr;
      if (!inScope(line, scope)) continue;
      auto it = std::find_if(run.updates.begin() + static_cast<std::ptrdiff_t>(cursor), run.updates.end(),
                             [&](const FixUpdate& u) { return u.sentence == line; });
      if (it != run.updates.end()) {
        state = &*it;
        cursor = static_cast<std::size_t>(it - run.updates.begin()) + 1;
        match = Match::kOurs;
      } else {
        match = log.find(line) == std::string::npos ? Match::kGenerated : Match::kNotDecoded;
      }
      continue;
    }
    if (line.rfind("{\"class\":\"TPV\"", 0) != 0 || match == Match::kNone) continue;
    ++r.tpv_after_fix;
    if (match == Match::kGenerated) {
      ++r.gpsd_generated;
      continue;
    }
    if (match == Match::kNotDecoded) {
      ++r.not_decoded;
      r.disagreements.push_back("not decoded: " + last_sentence);
      continue;
    }
    const auto& fix = state->fix;
    std::vector<std::string> bad;
    bool any = false;
    char buf[256];
    const auto lat = jsonNumber(line, "lat"), lon = jsonNumber(line, "lon");
    if (lat && lon && fix.position) {
      any = true;
      ++r.latlon;
      if (std::abs(*lat - fix.position->lat_deg) > kLatLonTolDeg ||
          std::abs(*lon - fix.position->lon_deg) > kLatLonTolDeg) {
        std::snprintf(buf, sizeof buf, "lat/lon gpsd %.9f,%.9f ours %.9f,%.9f", *lat, *lon, fix.position->lat_deg,
                      fix.position->lon_deg);
        bad.push_back(buf);
      }
    }
    if (const auto track = jsonNumber(line, "track"); track && fix.course_deg) {
      any = true;
      ++r.track;
      const double d = std::fmod(std::abs(*track - *fix.course_deg), 360.0);
      if (std::min(d, 360.0 - d) > kTrackTolDeg) {
        std::snprintf(buf, sizeof buf, "track gpsd %.4f ours %.4f", *track, *fix.course_deg);
        bad.push_back(buf);
      }
    }
    if (const auto speed = jsonNumber(line, "speed"); speed && fix.speed_mps) {
      any = true;
      ++r.speed;
      if (std::abs(*speed - *fix.speed_mps) > kSpeedTolMps) {
        std::snprintf(buf, sizeof buf, "speed gpsd %.3f ours %.4f", *speed, *fix.speed_mps);
        bad.push_back(buf);
      }
    }
    const bool gpsd_track = jsonNumber(line, "track").has_value(), gpsd_speed = jsonNumber(line, "speed").has_value();
    r.gpsd_only_latlon += lat && !fix.position;
    r.gpsd_only_track += gpsd_track && !fix.course_deg;
    r.gpsd_only_speed += gpsd_speed && !fix.speed_mps;
    r.ours_only_latlon += !lat && fix.position;
    if (std::getenv("NMEA_CORPUS_DEBUG") && ((lat && !fix.position) || (gpsd_track && !fix.course_deg) ||
                                             (gpsd_speed && !fix.speed_mps) || (!lat && fix.position))) {
      std::printf("ONE-SIDED %s: %s\n   after %s\n", name.c_str(), line.c_str(), last_sentence.c_str());
    }
    if (!any) continue;
    ++r.compared;
    bool all_known = true;
    for (const auto& b : bad) {
      bool known = false;
      for (std::size_t k = 0; k < kKnownDifferences.size(); ++k) {
        const auto& kd = kKnownDifferences[k];
        if (name == kd.file && last_sentence == kd.sentence && b.rfind(kd.field, 0) == 0) {
          known = true;
          r.known_used.insert(k);
        }
      }
      if (!known) {
        all_known = false;
        r.disagreements.push_back(b + " after " + last_sentence);
      }
    }
    if (bad.empty()) {
      ++r.agreed;
    } else if (all_known) {
      ++r.known;
    }
  }
  return r;
}

std::vector<std::pair<std::string, std::uint64_t>> counterList(const headingd::nmea::Counters& c) {
  std::vector<std::pair<std::string, std::uint64_t>> list;
  headingd::nmea::forEachCounter(c, [&](const char* name, std::uint64_t v) { list.emplace_back(name, v); });
  return list;
}

class GpsdLog : public ::testing::TestWithParam<std::string> {};

// Robustness on every file, binary ones included: whole, byte by byte or in random chunks,
// the same sentences and counters come out, the line buffer stays within its bound, and
// every good line is classified exactly once.
TEST_P(GpsdLog, ParsesTheSameWhateverTheChunking) {
  headingd::test_data::announce(kGpsdLogs);
  const std::string log = readFile(kLogsDir / GetParam());
  const ParseRun whole = parseLog(log, 1u, log.size() + 1);
  const ParseRun bytewise = parseLog(log, 2u, 1);
  const ParseRun random = parseLog(log, 3u, 300);
  for (const ParseRun* run : {&bytewise, &random}) {
    ASSERT_EQ(run->updates.size(), whole.updates.size());
    for (std::size_t i = 0; i < whole.updates.size(); ++i)
      ASSERT_EQ(run->updates[i].sentence, whole.updates[i].sentence);
    EXPECT_EQ(counterList(run->counters), counterList(whole.counters));
    EXPECT_EQ(run->comment_lines, whole.comment_lines);
    EXPECT_LE(run->max_buffered, headingd::nmea::FramerConfig{}.max_line_length);
  }
  const auto& c = whole.counters;
  EXPECT_EQ(c.sentences.ais + c.sentences.unsupported_talker + c.sentences.unsupported_type + c.sentences.malformed +
                c.sentences.decoded,
            c.framing.lines);
  EXPECT_EQ(c.sentences.decoded, whole.updates.size());
}

class GpsdCheck : public ::testing::TestWithParam<std::string> {};

TEST_P(GpsdCheck, AgreesWithGpsd) {
  headingd::test_data::announce(kGpsdLogs);
  const FileResult r = checkFile(GetParam());
  ASSERT_TRUE(r.has_chk);
  for (const auto& d : r.disagreements) ADD_FAILURE() << r.file << ": " << d;
  std::printf("%-36s tpv_after_fix=%zu compared=%zu agreed=%zu known=%zu\n", r.file.c_str(), r.tpv_after_fix,
              r.compared, r.agreed, r.known);
}

INSTANTIATE_TEST_SUITE_P(Corpus, GpsdLog, ::testing::ValuesIn(logFiles()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return testName(i.param); });
INSTANTIATE_TEST_SUITE_P(Corpus, GpsdCheck, ::testing::ValuesIn(logFilesWithChk()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return testName(i.param); });
// Without the data folder these lists are empty; AgreementTable then fails and says why.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(GpsdLog);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(GpsdCheck);

FileResult sum(const std::vector<std::string>& files, Scope scope, std::set<std::size_t>* known_used, bool print_rows);

void printRow(const FileResult& r) {
  const std::size_t disagree = r.compared - r.agreed - r.known + r.not_decoded;
  std::printf("%-33s %7zu %4zu %6zu %6zu %5zu %5zu | %6zu %5zu %5zu | %4zu %5zu %5zu | %7zu\n", r.file.c_str(),
              r.tpv_after_fix, r.gpsd_generated, r.compared, r.agreed, r.known, disagree, r.latlon, r.track, r.speed,
              r.gpsd_only_latlon, r.gpsd_only_track, r.gpsd_only_speed, r.ours_only_latlon);
}

FileResult sum(const std::vector<std::string>& files, Scope scope, std::set<std::size_t>* known_used, bool print_rows) {
  FileResult total;
  total.file = "TOTAL";
  total.has_chk = true;
  for (const auto& f : files) {
    const FileResult r = checkFile(f, scope);
    known_used->insert(r.known_used.begin(), r.known_used.end());
    if (!r.has_chk) {
      if (print_rows) std::printf("%-33s (no .chk: robustness only)\n", f.c_str());
      continue;
    }
    if (print_rows) {
      printRow(r);
      for (const auto& d : r.disagreements) std::printf("    %s\n", d.c_str());
    }
    total.tpv_after_fix += r.tpv_after_fix;
    total.gpsd_generated += r.gpsd_generated;
    total.not_decoded += r.not_decoded;
    total.compared += r.compared;
    total.agreed += r.agreed;
    total.known += r.known;
    total.latlon += r.latlon;
    total.track += r.track;
    total.speed += r.speed;
    total.gpsd_only_latlon += r.gpsd_only_latlon;
    total.gpsd_only_track += r.gpsd_only_track;
    total.gpsd_only_speed += r.gpsd_only_speed;
    total.ours_only_latlon += r.ours_only_latlon;
    if (!print_rows)
      total.disagreements.insert(total.disagreements.end(), r.disagreements.begin(), r.disagreements.end());
  }
  return total;
}

// The whole corpus in one table, and the exceptions list kept honest.
TEST(GpsdCorpus, AgreementTable) {
  headingd::test_data::announce(kGpsdLogs);
  const auto files = logFiles();
  ASSERT_FALSE(files.empty()) << "no .log files in " << kLogsDir;
  std::set<std::size_t> known_used;
  std::printf(
      "gpsd TPV reports after GGA/RMC/GNS vs our Fix after the same sentence.\n"
      "columns: reports | of those, after sentences gpsd made up from binary input | compared (>= 1 common\n"
      "field) | agreed | known gpsd quirks | disagreements | comparisons made per field | fields only gpsd\n"
      "has (its derived speed, quality-0 positions) | positions only we have (gpsd said mode 1)\n");
  std::printf("%-33s %7s %4s %6s %6s %5s %5s | %6s %5s %5s | %s %s %s | %s\n", "file", "reports", "gen", "compar",
              "agreed", "known", "disag", "latlon", "track", "speed", "g_ll", "g_trk", "g_spd", "ours_ll");
  const FileResult total = sum(files, Scope::kFixSentences, &known_used, true);
  printRow(total);
  EXPECT_EQ(total.compared, total.agreed + total.known);
  EXPECT_EQ(total.not_decoded, 0u);
  EXPECT_GT(total.compared, 0u);
  for (std::size_t k = 0; k < kKnownDifferences.size(); ++k) {
    EXPECT_TRUE(known_used.count(k)) << "stale known difference: " << kKnownDifferences[k].file << " "
                                     << kKnownDifferences[k].sentence;
  }
}

// A wider net: the reports after every sentence we decode, not only GGA/RMC/GNS.
TEST(GpsdCorpus, AgreementAfterEveryDecodedSentence) {
  headingd::test_data::announce(kGpsdLogs);
  std::set<std::size_t> known_used;
  FileResult total = sum(logFiles(), Scope::kAllDecoded, &known_used, false);
  total.file = "TOTAL (after any decoded sentence)";
  printRow(total);
  for (const auto& d : total.disagreements) ADD_FAILURE() << d;
  EXPECT_EQ(total.compared, total.agreed + total.known);
  EXPECT_GT(total.compared, 0u);
}

}  // namespace
