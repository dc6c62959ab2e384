// The black box's writer side with real files, a real FIFO for a stuck disk and /dev/full for
// a full one: lines in order in their streams' segments, rotation by size and age, the total
// cap over old and current recordings, drops counted and announced, errors survived.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <thread>

#include "daemon_test_support.hpp"
#include "headingd/daemon/loop/status_builder.hpp"
#include "headingd/daemon/recorder/recorder.hpp"
#include "headingd/daemon/recorder/recorder_folder.hpp"
#include "headingd/daemon/recorder/recorder_output.hpp"

namespace headingd::daemon {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using test::readFile;
using test::TempDir;
using test::waitUntil;

RecorderConfig configFor(const std::string& dir) {
  RecorderConfig c;
  c.dir = dir;
  return c;
}

// "<name> 000042 <padding>": a line whose number says where it belongs.
std::string numbered(const std::string& name, int i, std::size_t width = 40) {
  char head[32];
  std::snprintf(head, sizeof head, "%s %06d ", name.c_str(), i);
  std::string line = head;
  line.resize(std::max(width, line.size()), 'x');
  return line;
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A stream's segments in the folder, by number.
std::map<std::uint64_t, std::string> segmentsOf(const std::string& folder, const std::string& stream) {
  std::map<std::uint64_t, std::string> found;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const auto parsed = parseSegmentFileName(entry.path().filename().string());
    if (parsed && parsed->stream == stream) found[parsed->number] = entry.path().string();
  }
  return found;
}

std::string concatenated(const std::map<std::uint64_t, std::string>& segments) {
  std::string all;
  for (const auto& [number, path] : segments) all += readFile(path);
  return all;
}

std::uint64_t regularBytesUnder(const std::string& dir) {
  std::uint64_t bytes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file() && !entry.is_symlink()) bytes += entry.file_size();
  }
  return bytes;
}

// The number in "<name> NNNNNN ...", -1 for a note or another line.
int numberOf(const std::string& line) {
  const std::size_t space = line.find(' ');
  if (line.empty() || line[0] == '#' || space == std::string::npos) return -1;
  return std::stoi(line.substr(space + 1, 6));
}

// Checks that the lines are 0, 1, 2 ... with each gap announced just before by "# lost <gap>
// lines"; returns the lines present and the lines announced lost.
struct Continuity {
  int present = 0;
  std::uint64_t announced_lost = 0;
  int next = 0;  // the number after the last line
};
Continuity checkContinuity(const std::vector<std::string>& lines) {
  Continuity c;
  std::uint64_t pending = 0;
  static const std::regex note("# lost ([0-9]+) lines");
  for (const std::string& line : lines) {
    std::smatch m;
    if (std::regex_match(line, m, note)) {
      pending += std::stoull(m[1]);
      continue;
    }
    const int n = numberOf(line);
    EXPECT_EQ(static_cast<std::uint64_t>(n - c.next), pending) << "before line " << line;
    c.announced_lost += pending;
    pending = 0;
    c.next = n + 1;
    ++c.present;
  }
  c.announced_lost += pending;  // a note at the end: lines lost after the last one
  return c;
}

// Captures what spdlog's default logger says while it lives.
class LogCapture {
 public:
  LogCapture() : previous_(spdlog::default_logger()) {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(text_);
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", sink));
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  std::string text() {
    spdlog::default_logger()->flush();
    return text_.str();
  }
  int count(const std::string& what) {
    const std::string all = text();
    int n = 0;
    for (std::size_t at = all.find(what); at != std::string::npos; at = all.find(what, at + 1)) ++n;
    return n;
  }

 private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::logger> previous_;
};

TEST(Recorder, LinesArriveInOrderInTheirOwnStreamFilesBesideTheStartFiles) {
  TempDir dir;
  Recorder recorder(configFor(dir.path() + "/recordings"), {"can", "gps", "estimator"});
  EXPECT_THROW(recorder.stream("imu"), std::invalid_argument);
  EXPECT_FALSE(recorder.stream("can").write("before start: not recorded"));
  recorder.start({{"header.toml", "version = \"test\"\n"}, {"headingd.toml", "[daemon]\n"}});
  const std::string folder = recorder.folder();
  EXPECT_TRUE(std::regex_match(fs::path(folder).filename().string(),
                               std::regex("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}-[0-9]{2}-[0-9]{2}Z")))
      << folder;
  EXPECT_EQ(fs::path(folder).parent_path().string(), dir.path() + "/recordings");
  EXPECT_EQ(readFile(folder + "/header.toml"), "version = \"test\"\n");

  // Three producer threads at once, as the sources and the estimator loop will be.
  const int kLines = 3000;
  std::vector<std::thread> producers;
  std::atomic<int> refused{0};
  for (const std::string name : {"can", "gps", "estimator"}) {
    producers.emplace_back([&, name] {
      RecorderStream& s = recorder.stream(name);
      for (int i = 0; i < kLines; ++i) {
        while (!s.write(numbered(name, i))) {
          ++refused;  // the ring was full: this test wants every line, so it waits
          std::this_thread::sleep_for(1ms);
        }
      }
    });
  }
  for (auto& t : producers) t.join();
  recorder.stop();
  recorder.stop();  // idempotent
  EXPECT_FALSE(recorder.stream("can").write("after stop: not recorded"));

  for (const std::string name : {"can", "gps", "estimator"}) {
    const auto segments = segmentsOf(folder, name);
    ASSERT_EQ(segments.size(), 1u) << name;
    EXPECT_EQ(segments.begin()->second, folder + "/" + name + ".000001.log");
    std::string expected;
    for (int i = 0; i < kLines; ++i) expected += numbered(name, i) + "\n";
    EXPECT_EQ(readFile(segments.begin()->second), expected) << name;
  }
  const RecorderCounters c = recorder.counters();
  EXPECT_EQ(c.lines_written, 3u * kLines);
  EXPECT_EQ(c.bytes_written, 3u * kLines * 41u);
  EXPECT_EQ(c.lines_dropped_ring_full, static_cast<std::uint64_t>(refused.load()));
  EXPECT_EQ(c.lines_dropped_io, 0u);
  EXPECT_EQ(c.write_errors, 0u);
  EXPECT_EQ(c.segments_opened, 3u);
  EXPECT_EQ(c.bytes_on_disk, regularBytesUnder(dir.path() + "/recordings"));
}

TEST(Recorder, RefusesALineTooLongOrHoldingANewlineAndSaysWhereItWas) {
  TempDir dir;
  Recorder recorder(configFor(dir.path()), {"gps"});
  recorder.start({});
  RecorderStream& s = recorder.stream("gps");
  EXPECT_TRUE(s.write(numbered("gps", 0)));
  EXPECT_TRUE(s.write(std::string(RecorderStream::kMaxLineBytes, 'a').replace(0, 11, "gps 000001 ")));
  EXPECT_FALSE(s.write(std::string(RecorderStream::kMaxLineBytes + 1, 'b')));
  EXPECT_FALSE(s.write("gps 000003 with\na newline"));
  EXPECT_TRUE(s.write(numbered("gps", 4)));
  EXPECT_FALSE(s.write(std::string(300, 'c')));  // lost at the very end
  recorder.stop();
  const std::vector<std::string> lines = linesOf(readFile(recorder.folder() + "/gps.000001.log"));
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[2], "# lost 2 lines");
  EXPECT_EQ(lines[4], "# lost 1 lines");
  EXPECT_EQ(checkContinuity(lines).announced_lost, 3u);
  EXPECT_EQ(recorder.counters().lines_refused, 3u);
  EXPECT_EQ(recorder.counters().lines_written, 3u);
}

TEST(Recorder, RotatesASegmentBeyondItsSizeAndKeepsEveryLineInOrder) {
  TempDir dir;
  RecorderConfig config = configFor(dir.path());
  config.segment_max_bytes = 4096;
  Recorder recorder(config, {"can"});
  recorder.start({});
  const int kLines = 1000;  // 41 bytes each: 41 000 bytes, 10 segments of 99 lines and one of 10
  for (int i = 0; i < kLines; ++i) {
    while (!recorder.stream("can").write(numbered("can", i))) std::this_thread::sleep_for(1ms);
  }
  recorder.stop();
  const auto segments = segmentsOf(recorder.folder(), "can");
  ASSERT_EQ(segments.size(), 11u);
  std::uint64_t expected_number = 1;
  for (const auto& [number, path] : segments) {
    EXPECT_EQ(number, expected_number++);
    EXPECT_LE(fs::file_size(path), 4096u) << path;
    if (number < 11) {
      EXPECT_GT(fs::file_size(path), 4096u - 41u) << path;
    }
  }
  std::string expected;
  for (int i = 0; i < kLines; ++i) expected += numbered("can", i) + "\n";
  EXPECT_EQ(concatenated(segments), expected);
  EXPECT_EQ(recorder.counters().segments_opened, 11u);
  EXPECT_EQ(recorder.counters().lines_written, static_cast<std::uint64_t>(kLines));
}

TEST(Recorder, RotatesASegmentOlderThanItsAge) {
  TempDir dir;
  RecorderConfig config = configFor(dir.path());
  config.segment_max_age_s = 0.3;
  Recorder recorder(config, {"gps"});
  recorder.start({});
  const std::string first = recorder.folder() + "/gps.000001.log";
  ASSERT_TRUE(recorder.stream("gps").write(numbered("gps", 0)));
  // The segment is written out when it is closed for its age (or at the second's sync).
  ASSERT_TRUE(waitUntil([&] { return readFile(first) == numbered("gps", 0) + "\n"; }, 10s));
  std::this_thread::sleep_for(1s);  // well past the age: closed, whichever wrote it out
  ASSERT_TRUE(recorder.stream("gps").write(numbered("gps", 1)));
  recorder.stop();
  EXPECT_EQ(readFile(first), numbered("gps", 0) + "\n");
  EXPECT_EQ(readFile(recorder.folder() + "/gps.000002.log"), numbered("gps", 1) + "\n");
  EXPECT_EQ(recorder.counters().segments_opened, 2u);
}

// An old recording folder with a header and segments of `bytes` each, written at `age` ago
// (the segments one minute apart, the first the oldest).
void makeOldRecording(const std::string& folder, const std::vector<std::string>& segments, std::size_t bytes,
                      std::chrono::hours age) {
  fs::create_directories(folder);
  std::ofstream(folder + "/header.toml") << std::string(100, '#');
  auto when = fs::file_time_type::clock::now() - age;
  for (const std::string& name : segments) {
    std::ofstream(folder + "/" + name) << std::string(bytes, 'o');
    fs::last_write_time(folder + "/" + name, when);
    when += std::chrono::minutes(1);
  }
}

TEST(Recorder, TotalCapDeletesTheOldestSegmentsFirstThenOldFoldersAndKeepsTheCurrentOne) {
  TempDir dir;
  const std::string old1 = dir.file("2020-01-01T00-00-00Z");
  const std::string old2 = dir.file("2020-01-02T00-00-00Z");
  // In old1, gps.000001 was written to last, after can.000002.
  makeOldRecording(old1, {"can.000001.log", "can.000002.log", "gps.000001.log"}, 10000, std::chrono::hours(48));
  makeOldRecording(old2, {"can.000001.log"}, 10000, std::chrono::hours(24));
  dir.write("README", std::string(50, 'r'));  // not in a recording folder: counted, kept
  RecorderConfig config = configFor(dir.path());
  config.segment_max_bytes = 4096;
  config.total_max_bytes = 40000;
  Recorder recorder(config, {"can"});
  recorder.start({{"header.toml", std::string(200, 'h')}});
  // 40 450 bytes at start: the oldest segment goes at once.
  ASSERT_TRUE(waitUntil([&] { return recorder.counters().segments_deleted == 1; }, 10s));
  EXPECT_FALSE(fs::exists(old1 + "/can.000001.log"));
  EXPECT_TRUE(fs::exists(old1 + "/can.000002.log"));
  EXPECT_EQ(recorder.counters().bytes_on_disk, regularBytesUnder(dir.path()));

  // The next segment to go is old1's can.000002: its last write is older than gps.000001's,
  // though its number is higher.
  const int kFirstLines = 240;  // 9 840 bytes: 40 290 in all
  auto produce = [&](int from, int to) {
    for (int i = from; i < to; ++i) {
      while (!recorder.stream("can").write(numbered("can", i))) std::this_thread::sleep_for(1ms);
    }
  };
  produce(0, kFirstLines);
  ASSERT_TRUE(waitUntil([&] { return recorder.counters().segments_deleted == 2; }, 10s));
  EXPECT_FALSE(fs::exists(old1 + "/can.000002.log"));
  EXPECT_TRUE(fs::exists(old1 + "/gps.000001.log"));

  const int kLines = 1740;  // 71 340 bytes in 18 segments: every old segment goes, then this run's oldest
  produce(kFirstLines, kLines);
  recorder.stop();
  EXPECT_FALSE(fs::exists(old1)) << "an old folder without segments goes entirely";
  EXPECT_FALSE(fs::exists(old2));
  EXPECT_EQ(readFile(dir.file("README")), std::string(50, 'r'));
  EXPECT_EQ(readFile(recorder.folder() + "/header.toml"), std::string(200, 'h'));
  const auto kept = segmentsOf(recorder.folder(), "can");
  ASSERT_FALSE(kept.empty());
  EXPECT_EQ(kept.rbegin()->first, 18u) << "the last segment is kept";
  std::uint64_t expected_number = kept.begin()->first;
  for (const auto& [number, path] : kept) EXPECT_EQ(number, expected_number++) << "the oldest went first";
  // What is left is the end of what was written.
  std::string all;
  for (int i = 0; i < kLines; ++i) all += numbered("can", i) + "\n";
  const std::string tail = concatenated(kept);
  EXPECT_EQ(all.substr(all.size() - tail.size()), tail);

  const std::uint64_t on_disk = regularBytesUnder(dir.path());
  EXPECT_LE(on_disk, 40000u);
  EXPECT_GT(on_disk, 40000u - 4096u - 41u) << "no more was deleted than needed";
  const RecorderCounters c = recorder.counters();
  EXPECT_EQ(c.bytes_on_disk, on_disk);
  EXPECT_EQ(c.segments_deleted, 4u + (18u - kept.size()));
  EXPECT_EQ(c.write_errors, 0u);
}

TEST(Recorder, ProducerNeverWaitsForAStuckDiskItsDropsAreCountedAndAnnounced) {
  TempDir dir;
  RecorderConfig config = configFor(dir.path());
  config.ring_lines = 64;
  config.segment_max_bytes = 64ull << 20;
  LogCapture log;
  Recorder recorder(config, {"can"});
  recorder.start({});
  // The segment is a FIFO whose reader does not read yet: once the pipe is full,
  // the writer thread blocks in write(2), as on a stuck disk.
  const std::string segment = recorder.folder() + "/can.000001.log";
  ASSERT_EQ(mkfifo(segment.c_str(), 0600), 0) << std::strerror(errno);
  const int reader = open(segment.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  ASSERT_GE(reader, 0);
  std::string received;
  std::thread reading;
  auto start_reading = [&] {
    if (reading.joinable()) return;
    fcntl(reader, F_SETFL, fcntl(reader, F_GETFL) & ~O_NONBLOCK);
    reading = std::thread([&] {
      char chunk[65536];
      for (ssize_t n; (n = read(reader, chunk, sizeof chunk)) != 0;) {
        if (n > 0)
          received.append(chunk, static_cast<std::size_t>(n));
        else if (errno != EINTR)
          break;
      }
    });
  };
  struct Finally {
    std::function<void()> f;
    ~Finally() { f(); }
  } finally{[&] {
    start_reading();
    recorder.stop();
    reading.join();
    close(reader);
  }};

  RecorderStream& can = recorder.stream("can");
  int produced = 0, accepted = 0;
  // Full: less than a page free (the kernel does not always pack the last page).
  const int capacity = fcntl(reader, F_GETPIPE_SZ);
  auto pipe_full = [&] {
    int queued = 0;
    return ioctl(reader, FIONREAD, &queued) == 0 && queued > capacity - 4096;
  };
  // Gently until the writer is stuck (a pause now and then lets it keep up)...
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (!pipe_full() && std::chrono::steady_clock::now() < deadline) {
    accepted += can.write(numbered("can", produced++, 100)) ? 1 : 0;
    if (produced % 32 == 0) std::this_thread::sleep_for(1ms);
  }
  int queued = 0;
  ioctl(reader, FIONREAD, &queued);
  ASSERT_TRUE(pipe_full()) << "the writer has filled the pipe: " << queued << " of " << capacity << " bytes, "
                           << produced << " lines produced";
  // ... then flat out: nothing waits for the writer, the ring fills and lines are dropped.
  for (int i = 0; i < 5000; ++i) accepted += can.write(numbered("can", produced++, 100)) ? 1 : 0;
  EXPECT_GE(produced - accepted, 4000) << "the ring holds 64 lines, the pipe less than a page more";
  EXPECT_EQ(recorder.counters().lines_dropped_ring_full, static_cast<std::uint64_t>(produced - accepted));
  ASSERT_TRUE(waitUntil([&] { return log.count("ring of 64 lines was full") == 1; }, 10s)) << log.text();

  start_reading();  // the disk comes back
  ASSERT_TRUE(
      waitUntil([&] { return recorder.counters().lines_written == static_cast<std::uint64_t>(accepted); }, 20s));
  for (int i = 0; i < 10; ++i, ++produced) ASSERT_TRUE(can.write(numbered("can", produced, 100)));
  finally.f();
  finally.f = [] {};

  const Continuity c = checkContinuity(linesOf(received));
  EXPECT_EQ(c.next, produced);
  EXPECT_EQ(c.present, accepted + 10);
  const RecorderCounters counters = recorder.counters();
  EXPECT_EQ(c.announced_lost, counters.lines_dropped_ring_full);
  EXPECT_EQ(counters.lines_written, static_cast<std::uint64_t>(accepted + 10));
  EXPECT_EQ(counters.lines_dropped_io, 0u);
  EXPECT_EQ(log.count("ring of 64 lines was full"), 1) << log.text();
}

TEST(Recorder, AFullDiskDropsAndCountsLogsOnceAndWritingResumesInANewSegment) {
  TempDir dir;
  RecorderConfig config = configFor(dir.path());
  config.segment_max_bytes = 4096;
  LogCapture log;
  Recorder recorder(config, {"can"});
  recorder.start({});
  // The second segment is the kernel's full device: every write to it fails with ENOSPC.
  const std::string second = recorder.folder() + "/can.000002.log";
  ASSERT_EQ(symlink("/dev/full", second.c_str()), 0) << std::strerror(errno);
  RecorderStream& can = recorder.stream("can");
  int produced = 0;
  for (; produced < 150; ++produced) ASSERT_TRUE(can.write(numbered("can", produced)));  // 99 fill the first
  ASSERT_TRUE(waitUntil(
      [&] {
        const RecorderCounters c = recorder.counters();
        return c.write_errors >= 1 && c.lines_dropped_io >= 51;
      },
      10s));
  EXPECT_EQ(recorder.counters().lines_dropped_io, 51u) << "the lines after the first segment's 99";
  // During the back-off lines go nowhere (counted); after it a new segment is opened.
  ASSERT_TRUE(waitUntil(
      [&] {
        can.write(numbered("can", produced++));
        std::this_thread::sleep_for(50ms);
        return recorder.counters().segments_opened >= 3;
      },
      30s));
  for (int i = 0; i < 5; ++i, ++produced) ASSERT_TRUE(can.write(numbered("can", produced)));
  recorder.stop();

  const RecorderCounters c = recorder.counters();
  EXPECT_EQ(c.write_errors, 1u);
  EXPECT_EQ(c.segments_opened, 3u);
  EXPECT_EQ(c.lines_written + c.lines_dropped_io, static_cast<std::uint64_t>(produced));
  EXPECT_EQ(readFile(recorder.folder() + "/can.000001.log").size(), 99u * 41u);
  const std::vector<std::string> third = linesOf(readFile(recorder.folder() + "/can.000003.log"));
  ASSERT_FALSE(third.empty());
  EXPECT_EQ(third[0], "# lost " + std::to_string(c.lines_dropped_io) + " lines");
  std::vector<std::string> all = linesOf(readFile(recorder.folder() + "/can.000001.log"));
  all.insert(all.end(), third.begin(), third.end());
  const Continuity continuity = checkContinuity(all);
  EXPECT_EQ(continuity.next, produced);
  EXPECT_EQ(continuity.announced_lost, c.lines_dropped_io);
  EXPECT_EQ(log.count("cannot write " + second + ": No space left on device"), 1) << log.text();
  EXPECT_EQ(log.count("writing " + recorder.folder() + "/can.000003.log again"), 1) << log.text();
}

TEST(Recorder, ASegmentThatCannotBeOpenedIsTriedAgainUnderTheSameNumber) {
  TempDir dir;
  LogCapture log;
  Recorder recorder(configFor(dir.path()), {"gps"});
  recorder.start({});
  // A folder where the segment should be: open(2) fails with EISDIR until it is gone.
  const std::string first = recorder.folder() + "/gps.000001.log";
  fs::create_directory(first);
  RecorderStream& gps = recorder.stream("gps");
  int produced = 0;
  ASSERT_TRUE(gps.write(numbered("gps", produced++)));
  ASSERT_TRUE(waitUntil([&] { return recorder.counters().write_errors == 1; }, 10s));
  fs::remove(first);
  ASSERT_TRUE(waitUntil(
      [&] {
        gps.write(numbered("gps", produced++));
        std::this_thread::sleep_for(50ms);
        return recorder.counters().segments_opened == 1;
      },
      30s));
  recorder.stop();
  const std::vector<std::string> lines = linesOf(readFile(first));
  ASSERT_GE(lines.size(), 2u);
  const RecorderCounters c = recorder.counters();
  EXPECT_EQ(lines[0], "# lost " + std::to_string(c.lines_dropped_io) + " lines");
  EXPECT_EQ(checkContinuity(lines).next, produced);
  EXPECT_EQ(c.write_errors, 1u);
  EXPECT_EQ(log.count("cannot open " + first + ": Is a directory"), 1) << log.text();
  EXPECT_EQ(log.count("writing " + first + " again"), 1) << log.text();
}

TEST(Recorder, AFolderThatExistsGetsASuffixAndOneThatCannotBeMadeThrows) {
  TempDir dir;
  const auto t = std::chrono::system_clock::from_time_t(1700000000);  // 2023-11-14T22:13:20Z
  EXPECT_EQ(makeRecordingFolder(dir.path(), t, {}), dir.file("2023-11-14T22-13-20Z"));
  EXPECT_EQ(makeRecordingFolder(dir.path(), t, {}), dir.file("2023-11-14T22-13-20Z-2"));
  EXPECT_EQ(makeRecordingFolder(dir.path(), t, {{"a.toml", "x"}}), dir.file("2023-11-14T22-13-20Z-3"));
  EXPECT_EQ(readFile(dir.file("2023-11-14T22-13-20Z-3/a.toml")), "x");

  dir.write("plain-file", "");
  Recorder recorder(configFor(dir.file("plain-file") + "/recordings"), {"can"});
  try {
    recorder.start({});
    FAIL() << "start() made a folder under a file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("plain-file")), std::string::npos) << e.what();
  }
  EXPECT_FALSE(recorder.stream("can").write("not recorded"));
  EXPECT_EQ(recorder.counters().lines_dropped_ring_full, 0u);
}

TEST(Recorder, WhenOffStartSaysWhyOnceAndNothingIsWritten) {
  TempDir dir;
  LogCapture log;
  RecorderConfig config = configFor(dir.path());
  config.enabled = false;
  config.off_reason = "because the test says so";
  Recorder recorder(config, {"can"});
  recorder.start({{"header.toml", ""}});
  EXPECT_EQ(recorder.folder(), "");
  EXPECT_FALSE(recorder.stream("can").write("not recorded"));
  recorder.stop();
  EXPECT_TRUE(fs::is_empty(dir.path()));
  EXPECT_EQ(log.count("recorder: off: because the test says so"), 1) << log.text();
}

// The thread that starts the recorder may be real-time (the estimator's may be SCHED_FIFO);
// the writer, which can block in the disk, must not be.
TEST(Recorder, TheWriterThreadRunsAtNormalSchedulingWhenStartedFromARealTimeThread) {
  TempDir dir;
  Recorder recorder(configFor(dir.path()), {"can"});
  int start_error = 0;
  bool started_at_fifo = false;
  std::thread starter([&] {
    sched_param fifo{};
    fifo.sched_priority = 1;
    start_error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &fifo);
    if (start_error != 0) return;
    int policy = 0;
    sched_param now{};
    started_at_fifo = pthread_getschedparam(pthread_self(), &policy, &now) == 0 && policy == SCHED_FIFO;
    recorder.start({});
  });
  starter.join();
  // Without CAP_SYS_NICE or an RLIMIT_RTPRIO (an unprivileged user) there is no SCHED_FIFO
  // thread to start the recorder from, so nothing to check: skipped, saying why.
  if (start_error != 0) GTEST_SKIP() << "SCHED_FIFO refused here: " << std::strerror(start_error);
  ASSERT_TRUE(started_at_fifo);
  // The writer thread names itself "recorder".
  int writer_policy = -1;
  ASSERT_TRUE(waitUntil(
      [&] {
        for (const auto& task : fs::directory_iterator("/proc/self/task")) {
          if (readFile(task.path().string() + "/comm") == "recorder\n") {
            writer_policy = sched_getscheduler(std::stoi(task.path().filename().string()));
            return true;
          }
        }
        return false;
      },
      10s));
  EXPECT_EQ(writer_policy, SCHED_OTHER);
  recorder.stop();
}

TEST(RecorderNames, SegmentsAndFolderOrder) {
  EXPECT_EQ(segmentFileName("can", 1), "can.000001.log");
  EXPECT_EQ(segmentFileName("can", 1234567), "can.1234567.log");
  const auto parsed = parseSegmentFileName("estimator.000042.log");
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->stream, "estimator");
  EXPECT_EQ(parsed->number, 42u);
  EXPECT_FALSE(parseSegmentFileName("header.toml"));
  EXPECT_FALSE(parseSegmentFileName("can.42.log"));
  EXPECT_FALSE(parseSegmentFileName(".000001.log"));
  EXPECT_TRUE(recordingFolderBefore("2023-11-14T22-13-20Z", "2023-11-14T22-13-20Z-2"));
  EXPECT_TRUE(recordingFolderBefore("2023-11-14T22-13-20Z-9", "2023-11-14T22-13-20Z-10"));
  EXPECT_TRUE(recordingFolderBefore("2023-11-14T22-13-20Z-10", "2023-11-15T00-00-00Z"));
  EXPECT_FALSE(recordingFolderBefore("2023-11-15T00-00-00Z", "2023-11-14T22-13-20Z"));
}

TEST(RecorderStatus, CountersFollowTheLoopsOnesWithTheirNames) {
  status_t m;
  m.num_counters = 1;
  m.counters.resize(1);
  m.counters[0].name = "gps_epochs";
  RecorderCounters c;
  c.lines_written = 7;
  c.bytes_on_disk = 9;
  appendRecorderCounters(m, c);
  ASSERT_EQ(m.num_counters, 10);
  EXPECT_EQ(m.counters[1].name, "recorder_lines_written");
  EXPECT_EQ(m.counters[1].value, 7);
  EXPECT_EQ(m.counters[9].name, "recorder_bytes_on_disk");
  EXPECT_EQ(m.counters[9].value, 9);
}

}  // namespace
}  // namespace headingd::daemon
