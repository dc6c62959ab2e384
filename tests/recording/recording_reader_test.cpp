// A recording folder written the way the daemon's threads write it (candump lines with their
// notes, the serial reader's calls through GpsStreamRecorder, the estimator's placements)
// must read back as exactly the calls the live estimator got, in their order.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "headingd/can/can_config.hpp"
#include "headingd/can/candump_log.hpp"
#include "headingd/can/candump_writer.hpp"
#include "headingd/can/epoch_assembler.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "headingd/nmea/gps_observation_from_fix.hpp"
#include "headingd/recording/recording_format.hpp"
#include "headingd/recording/recording_reader.hpp"
#include "headingd/recording/stream_recorders.hpp"

namespace headingd::recording {
namespace {

constexpr std::int64_t kOffsetNs = 1'700'000'000'000'000'000;  // candump time minus estimator time

class FileSink final : public LineSink {
 public:
  explicit FileSink(const std::string& path) : out_(path) {}
  bool write(std::string_view line) override {
    out_ << line << '\n';
    return true;
  }
  void flush() { out_.flush(); }

 private:
  std::ofstream out_;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct Folder {
  Folder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "headingd-recording-test-XXXXXX").string();
    path = mkdtemp(pattern.data());
  }
  ~Folder() { std::filesystem::remove_all(path); }
  std::string file(const std::string& name) const { return path + "/" + name; }
  void write(const std::string& name, const std::string& text) const { std::ofstream(file(name)) << text; }
  std::string path;
};

bool sameSample(const core::ImuSample& a, const core::ImuSample& b) {
  return a.t_ns == b.t_ns && a.gyro_rad_s == b.gyro_rad_s && a.accel_m_s2 == b.accel_m_s2 && a.mag_uT == b.mag_uT &&
         a.has_mag == b.has_mag;
}

// The fixture's recording: 60 IMU samples at 100 Hz as CAN frames, the first GPS epochs of a
// real receiver's capture as serial reads, and placements as a live run would have made them.
class RecordingReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string can_table = std::regex_replace(slurp(HEADINGD_CONFIG_DIR "/can-headingd.toml"),
                                                     std::regex("dbc = \"dbc/headingd_imu.dbc\""), "dbc = \"imu.dbc\"");
    std::filesystem::copy_file(HEADINGD_CONFIG_DIR "/dbc/headingd_imu.dbc", folder.file("imu.dbc"));
    folder.write("header.toml",
                 "format = \"headingd-recording\"\nformat_version = 1\nprogram_version = \"test\"\n"
                 "start_utc = \"2026-12-02T00:00:00.000000Z\"\ncan_time_offset_ns = " +
                     std::to_string(kOffsetNs) + "\n");
    folder.write("config.toml", can_table + "\n[gps]\ndevice = \"/dev/null\"\n");
    writeCan();
    writeGps();
  }

  void writeCan() {
    const can::CanConfig config = can::loadCanConfigFile(HEADINGD_CONFIG_DIR "/can-headingd.toml");
    const can::DbcDatabase dbc = can::loadDbcFile(config.dbc_path);
    const can::ImuFrameCodec codec(config, dbc);
    std::vector<core::ImuSample> samples;
    for (int i = 0; i < 60; ++i) {
      core::ImuSample s;
      s.t_ns = 5'000'000'000 + i * 10'000'000;
      s.gyro_rad_s = core::Vec3(0.01 * i, -0.02, 0.03);
      s.accel_m_s2 = core::Vec3(0.1, 0.2, 9.81);
      s.mag_uT = core::Vec3(20.0, 1.0 * i, 40.0);
      s.has_mag = true;
      samples.push_back(s);
    }
    can::CandumpWriteOptions options;
    options.start_time_ns = kOffsetNs;
    std::ostringstream log;
    can::writeCandumpLog(samples, codec, options, log);
    // The live receiver's view: each line into the assembler; a '#dropped' note after the line
    // that completed sample 10 (its ring was full), the first segment ends after sample 30.
    can::EpochAssembler assembler(codec, can::epochSettingsFrom(config));
    std::istringstream lines(log.str());
    std::string line;
    std::ofstream out(folder.file("can.000001.log"));
    while (std::getline(lines, line)) {
      out << line << '\n';
      can::CanFrame frame = can::parseCandumpLine(line)->frame;
      frame.t_ns -= kOffsetNs;
      const can::AssembledSamples s = assembler.push(frame);
      for (int k = 0; k < s.count; ++k) {
        const core::ImuSample& sample = s.samples[static_cast<std::size_t>(k)];
        if (assembled_.size() == 10) {
          LineBuffer note;
          out << std::string_view(note, formatCanDropped(sample.t_ns + kOffsetNs, note)) << '\n';
        } else {
          reached_estimator_.push_back(sample);
        }
        assembled_.push_back(sample);
        if (assembled_.size() == 30) out = std::ofstream(folder.file("can.000002.log"));
      }
    }
    ASSERT_EQ(assembled_.size(), 60u);
  }

  void writeGps() {
    // The capture's sentences in reads of 50 bytes, 10 ms apart; the live assembler's fixes.
    std::string nmea;
    std::istringstream capture(slurp(HEADINGD_GPSD_LOG));
    std::string line;
    while (std::getline(capture, line)) {
      if (!line.empty() && line[0] == '$') nmea += line + "\r\n";
    }
    nmea.resize(std::min<std::size_t>(nmea.size(), 3000));
    FileSink sink(folder.file("gps.000001.log"));
    GpsStreamRecorder recorder(sink);
    nmea::EpochAssembler live(nmea::ParserConfig{}, [this](const nmea::Fix& fix, std::int64_t receive_ns) {
      epochs_.push_back(nmea::gpsObservationFromFix(fix, receive_ns));
    });
    std::int64_t t = 4'000'000'000;
    for (std::size_t at = 0; at < nmea.size(); at += 50, t += 10'000'000) {
      const std::span bytes(reinterpret_cast<const std::uint8_t*>(nmea.data()) + at,
                            std::min<std::size_t>(50, nmea.size() - at));
      recorder.fed(bytes, t);
      live.feed(bytes, t);
      if (at == 1000) {  // the line went quiet once
        recorder.epochCompleted(t + 1);
        live.completeEpoch();
      }
    }
    recorder.streamEnded(t);
    live.endOfStream();
    sink.flush();
    ASSERT_GE(epochs_.size(), 4u);
  }

  Folder folder;
  std::vector<core::ImuSample> assembled_, reached_estimator_;
  std::vector<core::GpsObservation> epochs_;
};

TEST_F(RecordingReaderTest, GivesTheLiveCallsInTheLiveOrder) {
  {
    // Epoch 0 before any sample, 1 after 5, 2 never went in (its ring was full), 3 after 20
    // and again nothing, 4 after the last sample.
    FileSink sink(folder.file("estimator.000001.log"));
    EstimatorStreamRecorder estimator(sink);
    estimator.gpsPlaced(epochs_[0].t_ns, 0);
    estimator.gpsPlaced(epochs_[1].t_ns, 5);
    estimator.gpsPlaced(epochs_[3].t_ns, 20);
    estimator.gpsPlaced(epochs_[4].t_ns, reached_estimator_.size());
  }
  const RecordingSetup setup = loadRecordingSetup(folder.path);
  RecordingReader reader(setup);
  EXPECT_EQ(reader.firstTimeNs(), epochs_[0].t_ns);
  std::vector<RecordingStep> steps;
  RecordingStep step;
  while (reader.next(step)) steps.push_back(step);

  const auto imu = [&](std::size_t i) { return reached_estimator_[i]; };
  std::vector<std::pair<char, std::size_t>> expected;  // ('i', sample) or ('g', epoch)
  expected.emplace_back('g', 0);
  for (std::size_t i = 0; i < reached_estimator_.size(); ++i) {
    expected.emplace_back('i', i);
    if (i + 1 == 5) expected.emplace_back('g', 1);
    if (i + 1 == 20) expected.emplace_back('g', 3);
  }
  expected.emplace_back('g', 4);
  ASSERT_EQ(steps.size(), expected.size());
  for (std::size_t k = 0; k < steps.size(); ++k) {
    if (expected[k].first == 'i') {
      ASSERT_EQ(steps[k].kind, RecordingStep::Kind::kImu) << k;
      EXPECT_TRUE(sameSample(steps[k].imu, imu(expected[k].second))) << "step " << k;
    } else {
      ASSERT_EQ(steps[k].kind, RecordingStep::Kind::kGps) << k;
      const core::GpsObservation& want = epochs_[expected[k].second];
      EXPECT_EQ(steps[k].gps.t_ns, want.t_ns);
      EXPECT_EQ(steps[k].gps.fix_ok, want.fix_ok);
      EXPECT_EQ(steps[k].gps.position.has_value(), want.position.has_value());
      EXPECT_EQ(steps[k].gps.course_rad, want.course_rad);
      EXPECT_EQ(steps[k].gps.speed_mps, want.speed_mps);
    }
  }
  const RecordingCounters& c = reader.counters();
  EXPECT_EQ(c.imu_samples, 59u);
  EXPECT_EQ(c.imu_dropped_live, 1u);
  EXPECT_EQ(c.gps_epochs, 4u);
  EXPECT_EQ(c.gps_epochs_not_placed, 1u);
  EXPECT_TRUE(reader.complete());
}

TEST_F(RecordingReaderTest, AnEpochTheGpsStreamDoesNotHoldIsAnError) {
  folder.write("estimator.000001.log", "123 g 3\n");
  const RecordingSetup setup = loadRecordingSetup(folder.path);
  RecordingReader reader(setup);
  RecordingStep step;
  try {
    while (reader.next(step)) {
    }
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("estimator.000001.log:1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such epoch"), std::string::npos) << e.what();
  }
}

TEST_F(RecordingReaderTest, LostLinesAndAMissingStartMakeItIncomplete) {
  folder.write("estimator.000001.log", "# lost 3 lines\n");
  {
    const RecordingSetup setup = loadRecordingSetup(folder.path);
    RecordingReader reader(setup);
    RecordingStep step;
    while (reader.next(step)) {
    }
    EXPECT_EQ(reader.counters().lost_lines, 3u);
    EXPECT_FALSE(reader.complete());
  }
  std::filesystem::remove(folder.file("can.000001.log"));
  std::filesystem::remove(folder.file("estimator.000001.log"));
  const RecordingSetup setup = loadRecordingSetup(folder.path);
  RecordingReader reader(setup);
  EXPECT_TRUE(reader.counters().start_missing);
  EXPECT_FALSE(reader.complete());
}

TEST(RecordingSetup, AFolderThatIsNoRecordingSaysSo) {
  Folder folder;
  try {
    loadRecordingSetup(folder.path);
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("header.toml"), std::string::npos) << e.what();
  }
  folder.write("header.toml", "format = \"something\"\n");
  EXPECT_THROW(loadRecordingSetup(folder.path), std::exception);
}

}  // namespace
}  // namespace headingd::recording
