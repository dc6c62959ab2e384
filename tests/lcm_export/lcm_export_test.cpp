// headingd-lcm-export on real LCM log files: every field of every headingd type comes back
// from the CSV (encoded again from the .lcm declarations, it gives the logged bytes),
// channel selection, renamed and unknown channels, and bad logs (truncated, garbage,
// undecodable) reported with their byte offset while what came before stays exported.
#include <gtest/gtest.h>

#include <fstream>

#include "headingd/lcm_export/lcm_log_reader.hpp"
#include "lcm_export_test_support.hpp"
#include "lcm_schema.hpp"

namespace headingd::lcm_export::test {
namespace {

// The fingerprint of each type, from the generated code (the tables hold no type column).
std::int64_t fingerprintOfType(const std::string& type) {
  if (type == "heading_t") return headingd::heading_t::getHash();
  if (type == "attitude_t") return headingd::attitude_t::getHash();
  if (type == "imu_t") return headingd::imu_t::getHash();
  if (type == "gps_t") return headingd::gps_t::getHash();
  if (type == "status_t") return headingd::status_t::getHash();
  throw std::runtime_error("no type " + type);
}

// Every row of `csv` encodes, from the .lcm declaration of `type`, to the logged bytes of
// the events on that channel, in order, with the log's timestamp and event number.
void expectTableHoldsEvents(const std::filesystem::path& csv, const std::string& type,
                            const std::vector<LoggedEvent>& events, const std::string& channel,
                            std::size_t expected_rows) {
  static const LcmSchema schema = readLcmSchema(HEADINGD_LCM_DIR);
  const CsvTableData table = readCsv(csv);
  ASSERT_GE(table.header.size(), 2u);
  EXPECT_EQ(table.header[0], "log_utime");
  EXPECT_EQ(table.header[1], "event");
  std::size_t row = 0;
  for (std::size_t i = 0; i < events.size() && row < table.rows.size(); ++i) {
    if (events[i].channel != channel) continue;
    SCOPED_TRACE(csv.filename().string() + " row " + std::to_string(row));
    const auto& cells = table.rows[row++];
    EXPECT_EQ(cells.at("log_utime"), std::to_string(events[i].utime));
    EXPECT_EQ(cells.at("event"),
              std::to_string(events[i].event_number >= 0 ? events[i].event_number : static_cast<std::int64_t>(i)));
    RowEncoder encoder(schema, table.header, cells);
    EXPECT_EQ(encoder.encode(type, fingerprintOfType(type)), events[i].data);
  }
  EXPECT_EQ(table.rows.size(), expected_rows);
}

std::vector<LoggedEvent> everyTypeOnItsChannel() {
  AwkwardValues v(1);
  std::vector<LoggedEvent> events;
  std::int64_t t = 1733120000000000;
  events.push_back(eventOf("HEADING", awkwardHeading(v), t += 10000));
  events.push_back(eventOf("ATTITUDE", awkwardAttitude(v), t += 10));
  events.push_back(eventOf("IMU", awkwardImu(v), t += 10));
  events.push_back(eventOf("GPS", awkwardGps(v), t += 10));
  // STATUS: a source appears in the second message, the first has repeated and empty
  // counter names, the third has fewer sources again.
  events.push_back(eventOf("STATUS", awkwardStatus(v, {"imu_can"}, 2, true), t += 10));
  events.push_back(eventOf("HEADING", awkwardHeading(v), t += 10000));
  events.push_back(eventOf("STATUS", awkwardStatus(v, {"imu_can", "gps"}, 3, false), t += 10));
  events.push_back(eventOf("IMU", awkwardImu(v), t += 10));
  events.push_back(eventOf("STATUS", awkwardStatus(v, {"gps"}, 0, false), t += 10));
  for (int i = 0; i < 40; ++i) events.push_back(eventOf("HEADING", awkwardHeading(v), t += 10000));
  return events;
}

std::size_t countOn(const std::vector<LoggedEvent>& events, const std::string& channel, std::size_t before = SIZE_MAX) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < events.size() && i < before; ++i) n += events[i].channel == channel ? 1 : 0;
  return n;
}

// Exports `log` into `work`; the log must be reported bad (status 1) with `message` on stderr.
void expectBadLog(const std::filesystem::path& work, const std::filesystem::path& log, const std::string& message) {
  const RunResult r = runExporter(work, log.string() + " --out-dir " + work.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(message), std::string::npos) << "expected: " << message << "\nstderr: " << r.err;
}

TEST(LcmExport, EveryFieldOfEveryTypeComesBackFromTheTables) {
  TempDir work;
  const auto events = everyTypeOnItsChannel();
  writeLcmLog(work.path() / "run.lcm", events);
  const RunResult r =
      runExporter(work.path(), (work.path() / "run.lcm").string() + " --out-dir " + (work.path() / "tables").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const auto& [channel, type] : std::vector<std::pair<std::string, std::string>>{{"HEADING", "heading_t"},
                                                                                      {"ATTITUDE", "attitude_t"},
                                                                                      {"IMU", "imu_t"},
                                                                                      {"GPS", "gps_t"},
                                                                                      {"STATUS", "status_t"}}) {
    expectTableHoldsEvents(work.path() / "tables" / (channel + ".csv"), type, events, channel,
                           countOn(events, channel));
  }
  // Nothing else in the folder: no temporary files left.
  EXPECT_EQ(
      std::distance(std::filesystem::directory_iterator(work.path() / "tables"), std::filesystem::directory_iterator()),
      5);
}

// The daemon's own messages: the demo capture played into an LCM log file (LCM's file
// provider), exported, every HEADING, ATTITUDE, GPS and STATUS row encoded again to the
// logged bytes, and one IMU row per sample played.
TEST(LcmExport, TheDaemonsLogOfTheDemoExportsEveryMessage) {
  TempDir work;
  const std::filesystem::path log = work.path() / "demo.lcm";
  const std::string play = "sh " HEADINGD_DEMO_PLAYBACK_TOML " " HEADINGD_CONFIG_DIR " " + log.string() + " > " +
                           (work.path() / "play.toml").string() + " && " HEADINGD_BIN " --config " +
                           (work.path() / "play.toml").string() + " --log-level error";
  ASSERT_EQ(std::system(play.c_str()), 0) << play;
  const auto events = readLcmLog(log);
  const RunResult r = runExporter(work.path(), log.string() + " --out-dir " + (work.path() / "tables").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const auto& [channel, type] : std::vector<std::pair<std::string, std::string>>{
           {"HEADING", "heading_t"}, {"ATTITUDE", "attitude_t"}, {"GPS", "gps_t"}, {"STATUS", "status_t"}}) {
    expectTableHoldsEvents(work.path() / "tables" / (channel + ".csv"), type, events, channel,
                           countOn(events, channel));
  }
  const CsvTableData status = readCsv(work.path() / "tables" / "STATUS.csv");
  ASSERT_FALSE(status.rows.empty());
  const std::string samples = status.rows.back().at("sources.candump_log.counters.samples_pushed");
  EXPECT_EQ(samples, "60001");
  EXPECT_EQ(std::to_string(countOn(events, "IMU")), samples);
  EXPECT_NE(r.out.find("IMU\timu_t\t" + samples + " rows"), std::string::npos) << r.out;
}

TEST(LcmExport, ColumnsFollowTheDeclarationsAndCountersAreKeyedByName) {
  TempDir work;
  const auto events = everyTypeOnItsChannel();
  writeLcmLog(work.path() / "run.lcm", events);
  ASSERT_EQ(runExporter(work.path(), (work.path() / "run.lcm").string() + " --out-dir " + work.path().string()).status,
            0);
  const auto attitude = readCsv(work.path() / "ATTITUDE.csv").header;
  const std::vector<std::string> expected_start{"log_utime",     "event",    "utime",   "sample_utime",
                                                "sample_age_us", "validity", "q_nb_0",  "q_nb_1",
                                                "q_nb_2",        "q_nb_3",   "roll_rad"};
  EXPECT_EQ(std::vector<std::string>(attitude.begin(), attitude.begin() + 11), expected_start);
  EXPECT_EQ(attitude[13], "q_covariance_0_0");
  EXPECT_EQ(attitude[14], "q_covariance_0_1");
  EXPECT_EQ(attitude[28], "q_covariance_3_3");

  const CsvTableData status = readCsv(work.path() / "STATUS.csv");
  const auto column = [&](const std::string& name) {
    return std::find(status.header.begin(), status.header.end(), name) - status.header.begin();
  };
  for (const char* name : {"counters.gate_gap", "counters.weird, \"name\"", "counters.#2.name", "counters.#3.value",
                           "sources.imu_can.kind", "sources.imu_can.counters.frames_1", "sources.gps.counters.frames_2",
                           "rings.imu.dropped"}) {
    EXPECT_LT(column(name), static_cast<std::ptrdiff_t>(status.header.size())) << name;
  }
  // Declaration order, sources in the order they appeared.
  EXPECT_LT(column("num_sources"), column("sources.imu_can.kind"));
  EXPECT_LT(column("sources.imu_can.counters.frames_2"), column("sources.gps.kind"));
  EXPECT_LT(column("sources.gps.counters.frames_2"), column("num_rings"));
  EXPECT_LT(column("publish_errors"), column("counters.gate_gap"));
  // A source absent from a message has empty cells; the gps source was not in the first.
  EXPECT_EQ(status.rows[0].at("sources.gps.kind"), "");
  EXPECT_EQ(status.rows[2].at("sources.imu_can.num_counters"), "");
  EXPECT_EQ(status.rows[0].at("counters.#2.name"), "gate_gap");
  EXPECT_EQ(status.rows[1].at("counters.#2.name"), "");
}

TEST(LcmExport, ChannelOptionPicksChannelsAndNamesOnesTheLogLacks) {
  TempDir work;
  const auto events = everyTypeOnItsChannel();
  writeLcmLog(work.path() / "run.lcm", events);
  const std::string log = (work.path() / "run.lcm").string();
  RunResult r = runExporter(
      work.path(), log + " --out-dir " + (work.path() / "a").string() + " --channel GPS --channel HEADING,STATUS");
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> files;
  for (const auto& f : std::filesystem::directory_iterator(work.path() / "a")) files.push_back(f.path().filename());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"GPS.csv", "HEADING.csv", "STATUS.csv"}));
  expectTableHoldsEvents(work.path() / "a" / "HEADING.csv", "heading_t", events, "HEADING", countOn(events, "HEADING"));

  r = runExporter(work.path(), log + " --out-dir " + (work.path() / "b").string() + " --channel IMU,HEDING");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no channel HEDING in the log (it has: ATTITUDE, GPS, HEADING, IMU, STATUS)"), std::string::npos)
      << r.err;
  EXPECT_TRUE(std::filesystem::exists(work.path() / "b" / "IMU.csv"));
}

TEST(LcmExport, TypeIsToldByFingerprintAndUnknownTypesAreCounted) {
  TempDir work;
  AwkwardValues v(3);
  std::vector<LoggedEvent> events;
  events.push_back(eventOf("front/heading", awkwardHeading(v), 1));
  events.push_back(LoggedEvent{"OTHER", {0x12, 0x34, 0x56, 0x78, 0x9a, 0xbc, 0xde, 0xf0, 1, 2, 3}, 2});
  events.push_back(eventOf("front/heading", awkwardHeading(v), 3));
  events.push_back(LoggedEvent{"OTHER", {1, 2}, 4});
  // One channel with two of headingd's types: a table for each.
  events.push_back(eventOf("MIXED", awkwardGps(v), 5));
  events.push_back(eventOf("MIXED", awkwardImu(v), 6));
  writeLcmLog(work.path() / "run.lcm", events);
  const RunResult r =
      runExporter(work.path(), (work.path() / "run.lcm").string() + " --out-dir " + work.path().string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("OTHER: 2 messages of unknown type not exported (fingerprint 0x123456789abcdef0)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(work.path() / "OTHER.csv"));
  expectTableHoldsEvents(work.path() / "front_heading.csv", "heading_t", events, "front/heading", 2);
  expectTableHoldsEvents(work.path() / "MIXED.gps_t.csv", "gps_t", {events.begin(), events.begin() + 5}, "MIXED", 1);
  EXPECT_EQ(readCsv(work.path() / "MIXED.imu_t.csv").rows.size(), 1u);
  EXPECT_NE(r.out.find("front/heading\theading_t\t2 rows"), std::string::npos) << r.out;
}

// A good log of every type, to be damaged by each test.
class LcmExportBadLog : public ::testing::Test {
 protected:
  TempDir work;
  const std::vector<LoggedEvent> events = everyTypeOnItsChannel();
  const std::filesystem::path log = work.path() / "run.lcm";
  const std::vector<std::uint64_t> offsets = writeLcmLog(log, events);
};

// Cut in the middle of event `cut`'s data: an error at that event's offset, every event
// before it in the tables.
TEST_F(LcmExportBadLog, TruncatedLogIsReportedAtTheCutEventAndEarlierEventsAreKept) {
  const std::size_t cut = 20;
  std::filesystem::resize_file(log, offsets[cut] + 28 + 4);
  expectBadLog(work.path(), log,
               log.string() + ": byte " + std::to_string(offsets[cut]) + ": truncated event: it needs " +
                   std::to_string(offsets[cut + 1] - offsets[cut]) +
                   " bytes, the file ends after 32; the 20 events before it are exported");
  expectTableHoldsEvents(work.path() / "HEADING.csv", "heading_t", events, "HEADING", countOn(events, "HEADING", cut));
  expectTableHoldsEvents(work.path() / "STATUS.csv", "status_t", events, "STATUS", countOn(events, "STATUS", cut));
  EXPECT_FALSE(std::filesystem::exists(work.path() / "HEADING.csv.tmp"));

  // Cut inside the 28-byte header of the last event.
  std::filesystem::resize_file(log, offsets[cut] + 10);
  expectBadLog(work.path(), log, "byte " + std::to_string(offsets[cut]) + ": truncated event: the file ends 10 bytes");
}

TEST_F(LcmExportBadLog, GarbageBetweenEventsIsReportedAtItsOffset) {
  const std::size_t after = 12;
  std::string bytes = readText(log);
  bytes.insert(offsets[after], "garbage in the middle");
  std::ofstream(log, std::ios::binary | std::ios::trunc) << bytes;
  expectBadLog(work.path(), log, "byte " + std::to_string(offsets[after]) + ": bad sync word 0x67617262");
  expectTableHoldsEvents(work.path() / "HEADING.csv", "heading_t", events, "HEADING",
                         countOn(events, "HEADING", after));
}

TEST(LcmExport, AbsurdLengthAndUndecodableMessageAreReportedAtTheirEvent) {
  TempDir work;
  AwkwardValues v(5);
  std::vector<LoggedEvent> events;
  for (int i = 0; i < 3; ++i) events.push_back(eventOf("HEADING", awkwardHeading(v), i));
  // A heading_t fingerprint with a body that is cut short.
  LoggedEvent broken = eventOf("HEADING", awkwardHeading(v), 3);
  ASSERT_GT(broken.data.size(), 5u);
  // erase, not resize(size - 5): gcc 12 under ASan cannot see that the size stays above 5 and
  // warns of a huge memset in resize's growing branch (-Werror=stringop-overflow).
  broken.data.erase(broken.data.end() - 5, broken.data.end());
  events.push_back(broken);
  events.push_back(eventOf("HEADING", awkwardHeading(v), 4));
  const std::filesystem::path log = work.path() / "run.lcm";
  const auto offsets = writeLcmLog(log, events);
  expectBadLog(work.path(), log,
               "byte " + std::to_string(offsets[3]) + ": event 3 on channel HEADING: heading_t message of");
  expectTableHoldsEvents(work.path() / "HEADING.csv", "heading_t", events, "HEADING", 3);

  // Data length field of event 1 (bytes 24..27 of its header) set to -1.
  std::string bytes = readText(log);
  for (int i = 0; i < 4; ++i) bytes[offsets[1] + 24 + i] = '\xff';
  std::ofstream(log, std::ios::binary | std::ios::trunc) << bytes;
  expectBadLog(work.path(), log, "byte " + std::to_string(offsets[1]) + ": absurd data length -1");
  EXPECT_EQ(readCsv(work.path() / "HEADING.csv").rows.size(), 1u);
}

// An event header that claims 200 MiB of data in a log of a few kB: reported as a cut event
// before anything is allocated (it was allocated first, and died of bad_alloc under a memory
// limit, exporting nothing).
TEST_F(LcmExportBadLog, ALengthBeyondTheFileIsNotAllocated) {
  const std::size_t at = 5;
  std::string bytes = readText(log);
  const std::uint8_t claimed[4] = {0x0C, 0x80, 0x00, 0x00};  // 209 715 200
  std::copy(std::begin(claimed), std::end(claimed), bytes.begin() + static_cast<std::ptrdiff_t>(offsets[at] + 24));
  std::ofstream(log, std::ios::binary | std::ios::trunc) << bytes;
  LcmLogReader reader(log);
  LcmLogEvent event;
  for (std::size_t i = 0; i < at; ++i) ASSERT_TRUE(reader.next(event));
  try {
    reader.next(event);
    ADD_FAILURE() << "read";
  } catch (const LcmLogError& e) {
    EXPECT_EQ(e.offset(), offsets[at]);
    EXPECT_NE(std::string(e.what()).find("truncated event: it needs "), std::string::npos) << e.what();
  }
  EXPECT_LT(event.data.capacity(), std::size_t{1} << 20);
  expectBadLog(work.path(), log, "byte " + std::to_string(offsets[at]) + ": truncated event: it needs ");
}

// A status_t whose num_sources says 50 000 000 in 100-odd bytes: reported at once (the
// generated decoder would allocate gigabytes before it found out), earlier rows kept.
TEST(LcmExport, CorruptCountIsReportedWithoutAllocatingIt) {
  TempDir work;
  AwkwardValues v(7);
  headingd::status_t status = awkwardStatus(v, {}, 0, false);
  status.state = "ok";
  status.reason = "";
  std::vector<LoggedEvent> events{eventOf("STATUS", status, 1), eventOf("STATUS", status, 2)};
  const std::size_t num_sources_at = 8 + 8 + (4 + 3) + (4 + 1) + 8;  // fingerprint, utime, state, reason, uptime_us
  const std::uint8_t huge[4] = {0x02, 0xFA, 0xF0, 0x80};             // 50 000 000
  std::copy(std::begin(huge), std::end(huge), events[1].data.begin() + num_sources_at);
  const std::filesystem::path log = work.path() / "run.lcm";
  const auto offsets = writeLcmLog(log, events);
  expectBadLog(work.path(), log,
               "byte " + std::to_string(offsets[1]) + ": event 1 on channel STATUS: status_t message of " +
                   std::to_string(events[1].data.size()) +
                   " bytes does not decode (a count or length that does not fit the message)");
  expectTableHoldsEvents(work.path() / "STATUS.csv", "status_t", events, "STATUS", 1);
}

TEST(LcmExport, MissingLogAndBadArgumentsHaveTheirExitStatus) {
  TempDir work;
  RunResult r = runExporter(work.path(), (work.path() / "none.lcm").string() + " --out-dir " + work.path().string());
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("none.lcm: cannot open"), std::string::npos) << r.err;
  r = runExporter(work.path(), "--out-dir " + work.path().string());
  EXPECT_EQ(r.status, 2);
}

// A log named like one of its tables, exported into its own folder: the table's rename would
// have replaced the log. Refused (also through a symbolic link), the log left as it was.
TEST(LcmExport, ATableThatWouldBeTheLogItselfIsRefused) {
  TempDir work;
  const auto events = everyTypeOnItsChannel();
  writeLcmLog(work.path() / "HEADING.csv", events);
  const std::string before = readText(work.path() / "HEADING.csv");
  RunResult r = runExporter(work.path(), (work.path() / "HEADING.csv").string() + " --out-dir " + work.path().string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("would be the log"), std::string::npos) << r.err;
  std::filesystem::create_directory(work.path() / "linked");
  std::filesystem::create_symlink(work.path() / "HEADING.csv", work.path() / "linked" / "HEADING.csv");
  r = runExporter(work.path(),
                  (work.path() / "HEADING.csv").string() + " --out-dir " + (work.path() / "linked").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(readText(work.path() / "HEADING.csv"), before);
  EXPECT_FALSE(std::filesystem::exists(work.path() / "GPS.csv"));
}

}  // namespace
}  // namespace headingd::lcm_export::test
