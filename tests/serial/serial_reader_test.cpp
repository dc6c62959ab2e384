// SerialGpsReader against a real pseudo-terminal fed with real receiver captures
// (data/gpsd-logs): the fixes it delivers are the pure parser's, bit for bit, with its
// counters; garbage on the line is counted and changes no fix; an unplugged device (pty
// closed, symlink re-pointed to a new one) is reopened; a path that does not exist yet or
// is not a tty is retried with a bounded back-off.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <mutex>
#include <random>

#include "headingd/nmea/serial_gps_reader.hpp"
#include "pty_fixture.hpp"
#include "serial_reader_harness.hpp"
#include "serial_test_support.hpp"
#include "test_data.hpp"

namespace headingd::test {
namespace {

using nmea::SerialGpsConfig;
using nmea::SerialGpsCounters;
using nmea::SerialGpsReader;
using nmea::SerialGpsState;

// A capture of gpsd's corpus (../shared/data/gpsd-logs, else tests/data/gpsd-logs), announced.
std::filesystem::path gpsdLog(const std::string& name) { return test_data::file(test_data::kGpsdLogs, name); }

// ---------------------------------------------------------------------------------------

class CaptureOverPty : public ::testing::TestWithParam<const char*> {};

TEST_P(CaptureOverPty, DeliversTheParsersFixesAndCounters) {
  const auto wire = readWireBytes(gpsdLog(GetParam()));
  nmea::Counters want_counters;
  const auto want = referenceEpochs(wire, &want_counters);
  ASSERT_GE(want.size(), 5u) << "capture too short to show anything";

  PtyPair pty;
  Harness h(testConfig(pty.slavePath()));
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen));
  const std::int64_t t_start = monotonicNs();
  pty.writePaced(wire, lineBytesPerSecond(115200));
  const std::int64_t t_written = monotonicNs();
  ASSERT_TRUE(h.waitBytes(wire.size()));
  ASSERT_TRUE(waitFor([&] { return h.received.fixCount() >= want.size(); }, std::chrono::seconds(3)));

  expectSameFixes(h.received.fixesCopy(), want);
  const SerialGpsCounters c = h.counters();
  expectCountersEqual(c.parser, want_counters);
  EXPECT_EQ(c.epochs.epochs, want.size());
  EXPECT_EQ(c.epochs.late_sentences, 0u);
  EXPECT_EQ(c.read_errors, 0u);
  EXPECT_EQ(c.disconnects, 0u);
  EXPECT_EQ(c.state, SerialGpsState::kOpen);
  std::lock_guard lock(h.received.mutex);
  EXPECT_EQ(h.received.lines, want_counters.framing.lines);
  // Receive times: monotonic clock, in order, while the bytes were being written, and
  // never after the fix was handed out.
  for (std::size_t i = 0; i < h.received.receive_ns.size(); ++i) {
    EXPECT_GE(h.received.receive_ns[i], t_start);
    EXPECT_LE(h.received.receive_ns[i], t_written + 100'000'000);
    EXPECT_LE(h.received.receive_ns[i], h.received.delivered_ns[i]);
    if (i > 0) {
      EXPECT_GE(h.received.receive_ns[i], h.received.receive_ns[i - 1]);
    }
  }
}

// NMEA receivers of several makes; ublox-8.log has UBX binary packets between sentences.
INSTANTIATE_TEST_SUITE_P(GpsdLogs, CaptureOverPty,
                         ::testing::Values("mt3339.log", "sirfstarv-nmea.log", "furuno_gl_ga.log", "garmin-geko201.log",
                                           "bu353s4.log", "GPSmap-76S.log", "ublox-8.log"),
                         [](const auto& info) {
                           std::string n;
                           for (const char ch : std::string(info.param)) n += std::isalnum(ch) ? ch : '_';
                           return n;
                         });

// At a real receiver's line rate, 9600 baud: epochs come out one burst at a time, each as
// soon as the line goes quiet after it, stamped when its last sentence arrived.
TEST(SerialGpsReader, RealLineRateDeliversEachEpochAtTheEndOfItsBurst) {
  // Three epochs of a 1 Hz receiver, paced as it sent them: burst, one second, burst.
  const auto wire = readWireBytes(gpsdLog("garmin48.log"));
  const auto want = referenceEpochs(wire);
  ASSERT_GE(want.size(), 3u);
  PtyPair pty;
  SerialGpsConfig config = testConfig(pty.slavePath());
  config.baud = 9600;
  config.epoch_idle_s = 0.15;
  Harness h(config);
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen));

  // Cut the capture at each sentence that starts a new epoch.
  std::vector<std::size_t> cuts;
  {
    nmea::Parser p;
    std::vector<nmea::FixUpdate> u;
    std::optional<std::int64_t> tod;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < wire.size(); ++i) {
      if (wire[i] != '\n') continue;
      p.feed(std::span(wire).subspan(line_start, i + 1 - line_start), u);
      for (const auto& x : u) {
        if (x.fix.time_of_day_ns && x.fix.time_of_day_ns != tod) {
          if (tod) cuts.push_back(line_start);
          tod = x.fix.time_of_day_ns;
        }
      }
      u.clear();
      line_start = i + 1;
    }
  }
  ASSERT_GE(cuts.size(), 2u);
  std::size_t from = 0;
  for (int burst = 0; burst < 3; ++burst) {
    const std::size_t to = cuts[static_cast<std::size_t>(burst)];
    const std::int64_t t0 = monotonicNs();
    pty.writePaced(std::span(wire).subspan(from, to - from), lineBytesPerSecond(9600));
    const std::int64_t t1 = monotonicNs();
    ASSERT_TRUE(
        waitFor([&] { return h.received.fixCount() >= static_cast<std::size_t>(burst + 1); }, std::chrono::seconds(2)));
    {
      std::lock_guard lock(h.received.mutex);
      EXPECT_EQ(h.received.fixes.back(), want[static_cast<std::size_t>(burst)]);
      const std::int64_t rx = h.received.receive_ns.back();
      EXPECT_GE(rx, t0);
      EXPECT_LE(rx, t1 + 50'000'000) << "stamped with its last byte, not when delivered";
      const std::int64_t delivered_after_ms = (h.received.delivered_ns.back() - rx) / 1'000'000;
      EXPECT_GE(delivered_after_ms, 140) << "the line must be quiet for epoch_idle_s";
      EXPECT_LE(delivered_after_ms, 600) << "delivered at the end of its burst, not a second later";
    }
    from = to;
  }
  EXPECT_EQ(h.counters().epochs.late_sentences, 0u);
}

TEST(SerialGpsReader, GarbageBetweenSentencesIsCountedAndChangesNoFix) {
  const auto clean = readWireBytes(gpsdLog("mt3339.log"));
  nmea::Counters want_counters;
  const auto want = referenceEpochs(clean, &want_counters);

  // After every third line: a burst of line noise (no '$', '!', CR or LF, so it cannot
  // start or end a line), and every tenth line sent again with one character corrupted.
  std::mt19937 rng(7);
  std::vector<std::uint8_t> dirty;
  std::uint64_t noise_bytes = 0, corrupted = 0;
  std::size_t line_no = 0, line_start = 0;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    dirty.push_back(clean[i]);
    if (clean[i] != '\n') continue;
    ++line_no;
    if (line_no % 3 == 0) {
      const int n = 1 + static_cast<int>(rng() % 40);
      for (int k = 0; k < n; ++k) {
        std::uint8_t b;
        do b = static_cast<std::uint8_t>(rng());
        while (b == '$' || b == '!' || b == '\r' || b == '\n');
        dirty.push_back(b);
        ++noise_bytes;
      }
    }
    if (line_no % 10 == 0 && clean[line_start] == '$' && i - line_start > 12) {
      std::vector<std::uint8_t> copy(clean.begin() + static_cast<std::ptrdiff_t>(line_start),
                                     clean.begin() + static_cast<std::ptrdiff_t>(i + 1));
      copy[5] = copy[5] == 'X' ? 'Y' : 'X';  // in the address: the checksum no longer matches
      dirty.insert(dirty.end(), copy.begin(), copy.end());
      ++corrupted;
    }
    line_start = i + 1;
  }
  ASSERT_GT(noise_bytes, 100u);
  ASSERT_GT(corrupted, 5u);

  PtyPair pty;
  Harness h(testConfig(pty.slavePath()));
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen));
  pty.writePaced(dirty, lineBytesPerSecond(115200));
  ASSERT_TRUE(h.waitBytes(dirty.size()));
  ASSERT_TRUE(waitFor([&] { return h.received.fixCount() >= want.size(); }, std::chrono::seconds(3)));

  expectSameFixes(h.received.fixesCopy(), want);
  const auto c = h.counters();
  EXPECT_EQ(c.parser.framing.bytes, dirty.size());
  EXPECT_EQ(c.parser.framing.garbage_bytes, want_counters.framing.garbage_bytes + noise_bytes);
  EXPECT_EQ(c.parser.framing.bad_checksum, want_counters.framing.bad_checksum + corrupted);
  EXPECT_EQ(c.parser.framing.lines, want_counters.framing.lines);
  EXPECT_EQ(c.parser.sentences.decoded, want_counters.sentences.decoded);
}

// The receiver unplugged and plugged in again: the udev-style symlink the reader was
// configured with goes and the pty is closed; a new pty is created and the symlink points at
// it again.
TEST(SerialGpsReader, ReopensWhenTheDeviceComesBackBehindItsSymlink) {
  const auto wire = readWireBytes(gpsdLog("sirfstarv-nmea.log"));
  nmea::Counters want_counters;
  const auto want = referenceEpochs(wire, &want_counters);
  // Unplug between two epochs, halfway through: cut before the line starting epoch n/2.
  std::size_t cut = 0;
  {
    nmea::Parser p;
    std::vector<nmea::FixUpdate> u;
    std::size_t epochs_started = 0, line_start = 0;
    std::optional<std::int64_t> tod;
    for (std::size_t i = 0; i < wire.size() && cut == 0; ++i) {
      if (wire[i] != '\n') continue;
      p.feed(std::span(wire).subspan(line_start, i + 1 - line_start), u);
      for (const auto& x : u) {
        if (x.fix.time_of_day_ns && x.fix.time_of_day_ns != tod) {
          tod = x.fix.time_of_day_ns;
          if (++epochs_started == want.size() / 2 + 1) cut = line_start;
        }
      }
      u.clear();
      line_start = i + 1;
    }
  }
  ASSERT_GT(cut, 0u);

  TempDir dir;
  const auto link = dir.path() / "gps0";
  auto first = std::make_unique<PtyPair>();
  pointSymlink(link, first->slavePath());
  Harness h(testConfig(link.string()));
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen));
  first->writePaced(std::span(wire).first(cut), lineBytesPerSecond(115200));
  ASSERT_TRUE(h.waitBytes(cut));

  // Unplugged: udev removes the by-id link, the device goes. Without the first step the link
  // would dangle at /dev/pts/N, a number the kernel hands to the next pty anyone opens (another
  // test running beside this one), and the reader would rightly open that.
  std::filesystem::remove(link);
  first->close();
  ASSERT_TRUE(h.waitState(SerialGpsState::kWaitingForDevice));
  EXPECT_EQ(h.received.fixCount(), want.size() / 2) << "the epoch in progress goes out when the device goes";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a few retries against the dead path
  auto c = h.counters();
  EXPECT_EQ(c.state, SerialGpsState::kWaitingForDevice) << c.last_error;
  EXPECT_EQ(c.disconnects, 1u);
  EXPECT_EQ(c.reopens, 0u);
  EXPECT_GE(c.reopen_attempts, 1u);

  PtyPair second;  // plugged in again
  pointSymlink(link, second.slavePath());
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen));
  second.writePaced(std::span(wire).subspan(cut), lineBytesPerSecond(115200));
  ASSERT_TRUE(h.waitBytes(wire.size()));
  ASSERT_TRUE(waitFor([&] { return h.received.fixCount() >= want.size(); }, std::chrono::seconds(3)));

  expectSameFixes(h.received.fixesCopy(), want);
  c = h.counters();
  expectCountersEqual(c.parser, want_counters);
  EXPECT_EQ(c.disconnects, 1u);
  EXPECT_EQ(c.reopens, 1u);
  EXPECT_EQ(c.epochs.late_sentences, 0u);
  EXPECT_NE(c.last_error.find("gps0"), std::string::npos) << c.last_error;
}

// udev re-points the symlink to a new device while the old one lingers without failing
// reads: the periodic path check notices and switches.
TEST(SerialGpsReader, FollowsASymlinkRepointedWhileTheOldDeviceStaysOpen) {
  const auto wire = readWireBytes(gpsdLog("bu353s4.log"));
  const auto want = referenceEpochs(wire);
  TempDir dir;
  const auto link = dir.path() / "gps0";
  PtyPair old_device;
  pointSymlink(link, old_device.slavePath());
  Harness h(testConfig(link.string()));
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen));

  PtyPair new_device;
  pointSymlink(link, new_device.slavePath());
  ASSERT_TRUE(waitFor([&] { return h.counters().reopens == 1; }, std::chrono::seconds(3)));
  new_device.writePaced(wire, lineBytesPerSecond(115200));
  ASSERT_TRUE(h.waitBytes(wire.size()));
  ASSERT_TRUE(waitFor([&] { return h.received.fixCount() >= want.size(); }, std::chrono::seconds(3)));
  expectSameFixes(h.received.fixesCopy(), want);
  const auto c = h.counters();
  EXPECT_EQ(c.disconnects, 1u);
  EXPECT_NE(c.last_error.find("another device"), std::string::npos) << c.last_error;
}

TEST(SerialGpsReader, WaitsForADeviceThatDoesNotExistYet) {
  const auto wire = readWireBytes(gpsdLog("GPSmap-76S.log"));
  const auto want = referenceEpochs(wire);
  TempDir dir;
  const auto link = dir.path() / "gps0";
  Harness h(testConfig(link.string()));
  ASSERT_TRUE(h.waitState(SerialGpsState::kWaitingForDevice));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  auto c = h.counters();
  EXPECT_EQ(c.state, SerialGpsState::kWaitingForDevice);
  EXPECT_NE(c.last_error.find(link.string()), std::string::npos) << c.last_error;
  EXPECT_NE(c.last_error.find("does not exist"), std::string::npos) << c.last_error;
  // Back-off 0.05, 0.1, 0.2, 0.2 s...: about five attempts in half a second, not thousands.
  EXPECT_GE(c.open_attempts, 3u);
  EXPECT_LE(c.open_attempts, 8u);

  PtyPair pty;
  pointSymlink(link, pty.slavePath());
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen, std::chrono::seconds(2)));
  pty.writePaced(wire, lineBytesPerSecond(115200));
  ASSERT_TRUE(h.waitBytes(wire.size()));
  ASSERT_TRUE(waitFor([&] { return h.received.fixCount() >= want.size(); }, std::chrono::seconds(3)));
  expectSameFixes(h.received.fixesCopy(), want);
  EXPECT_EQ(h.counters().reopens, 0u) << "the first open is not a reopen";
}

TEST(SerialGpsReader, APathThatIsNotATtyIsReportedAndRetriedWithBoundedBackoff) {
  TempDir dir;
  const auto file = dir.path() / "not-a-tty";
  std::ofstream(file) << "$GPGGA\n";
  Harness h(testConfig(file.string()));
  ASSERT_TRUE(h.waitState(SerialGpsState::kError));
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  const auto c = h.counters();
  EXPECT_EQ(c.state, SerialGpsState::kError);
  EXPECT_NE(c.last_error.find("not a tty"), std::string::npos) << c.last_error;
  EXPECT_NE(c.last_error.find(file.string()), std::string::npos) << c.last_error;
  // Attempts at 0, .05, .15, .35, .55, .75, .95 s: the back-off grows to its maximum and
  // stays there.
  EXPECT_GE(c.open_attempts, 5u);
  EXPECT_LE(c.open_attempts, 9u);
  EXPECT_EQ(c.parser.framing.bytes, 0u);
}

TEST(SerialGpsReader, StopClosesThePortAndDeliversTheEpochInProgress) {
  const auto wire = readWireBytes(gpsdLog("mt3339.log"));
  const auto want = referenceEpochs(wire);
  PtyPair pty;
  SerialGpsConfig config = testConfig(pty.slavePath());
  config.epoch_idle_s = 0.0;  // only the next epoch, or stop(), completes one
  Harness h(config);
  ASSERT_TRUE(h.waitState(SerialGpsState::kOpen));
  pty.write(wire);
  ASSERT_TRUE(h.waitBytes(wire.size()));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(h.received.fixCount(), want.size() - 1) << "the last epoch waits for the next one";
  h.stop();
  expectSameFixes(h.received.fixesCopy(), want);
  const auto c = h.counters();
  EXPECT_EQ(c.state, SerialGpsState::kStopped);
  EXPECT_EQ(c.disconnects, 0u);
  // Nothing is read any more: bytes written now stay in the pty.
  pty.write(std::span(wire).first(100));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(h.counters().parser.framing.bytes, wire.size());
}

}  // namespace
}  // namespace headingd::test
