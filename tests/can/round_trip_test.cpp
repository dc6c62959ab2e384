// IMU CSV -> candump log (DBC encoder) -> log parser -> epoch assembler -> samples equal to
// the CSV within the DBC resolution. Real files: the bundled BROAD recording and a temp log.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "can_test_support.hpp"
#include "headingd/can/candump_log.hpp"
#include "headingd/can/candump_writer.hpp"
#include "headingd/can/epoch_assembler.hpp"
#include "headingd/files/imu_csv.hpp"

namespace headingd::can {
namespace {

struct ReplayResult {
  std::vector<core::ImuSample> samples;
  AssemblerCounters assembler;
  CandumpCounters log;
};

ReplayResult replayLog(const std::string& path, const ImuFrameCodec& codec, const EpochSettings& settings) {
  ReplayResult r;
  std::ifstream in(path);
  CandumpReader reader(in);
  EpochAssembler assembler(codec, settings);
  auto take = [&](const AssembledSamples& out) {
    for (int i = 0; i < out.count; ++i) r.samples.push_back(out.samples[static_cast<std::size_t>(i)]);
  };
  while (auto f = reader.next()) take(assembler.push(*f));
  take(assembler.finish());
  r.assembler = assembler.counters();
  r.log = reader.counters();
  return r;
}

void expectMatches(const std::vector<core::ImuSample>& csv, const ReplayResult& r, std::int64_t start_ns,
                   int mag_every) {
  ASSERT_EQ(r.samples.size(), csv.size());
  double gyro_err = 0, accel_err = 0, mag_err = 0;
  for (std::size_t i = 0; i < csv.size(); ++i) {
    const auto& got = r.samples[i];
    const auto& want = csv[i];
    // candump logs keep microseconds.
    ASSERT_LE(std::llabs(got.t_ns - start_ns - want.t_ns), 1000) << "row " << i;
    gyro_err = std::max(gyro_err, (got.gyro_rad_s - want.gyro_rad_s).cwiseAbs().maxCoeff());
    accel_err = std::max(accel_err, (got.accel_m_s2 - want.accel_m_s2).cwiseAbs().maxCoeff());
    ASSERT_EQ(got.has_mag, i % static_cast<std::size_t>(mag_every) == 0) << "row " << i;
    if (got.has_mag) mag_err = std::max(mag_err, (got.mag_uT - want.mag_uT).cwiseAbs().maxCoeff());
  }
  // Half a step of headingd_imu.dbc: 1e-4 rad/s, 2e-4 m/s^2, 0.002 uT.
  EXPECT_LE(gyro_err, 0.5e-4 + 1e-9);
  EXPECT_LE(accel_err, 1e-4 + 1e-9);
  EXPECT_LE(mag_err, 1e-3 + 1e-9);
}

class RoundTrip : public ::testing::TestWithParam<int> {};

TEST_P(RoundTrip, BroadRecordingThroughHeadingdFrames) {
  const int mag_every = GetParam();
  const auto csv = files::readImuCsv(HEADINGD_DEMO_IMU_CSV);
  ASSERT_GT(csv.size(), 1000u);
  const CanSetup setup = loadCanSetup(test::configPath("can-headingd.toml"));
  const ImuFrameCodec codec(setup.config, setup.dbc);
  test::TempDir dir;
  const std::string log_path = dir.path() + "/imu.log";
  CandumpWriteOptions options;
  options.mag_every = mag_every;
  {
    std::ofstream out(log_path);
    const CandumpWriteStats stats = writeCandumpLog(csv, codec, options, out);
    EXPECT_EQ(stats.clamped_values, 0u);
    EXPECT_EQ(stats.epochs, csv.size());
  }
  const ReplayResult r = replayLog(log_path, codec, epochSettingsFrom(setup.config));
  EXPECT_EQ(r.log.bad_lines, 0u);
  EXPECT_EQ(r.assembler.incomplete_epochs, 0u);
  EXPECT_EQ(r.assembler.sequence_gaps, 0u);
  EXPECT_EQ(r.assembler.unknown_id_frames, 0u);
  expectMatches(csv, r, options.start_time_ns, mag_every);
}

INSTANTIATE_TEST_SUITE_P(MagEvery, RoundTrip, ::testing::Values(1, 3));

#ifdef HEADINGD_CANDUMP_FROM_CSV_BIN
// The command-line tool writes the same log as the library call.
TEST(CandumpFromCsvTool, WritesALogThatReplaysToTheCsv) {
  test::TempDir dir;
  const std::string log_path = dir.path() + "/tool.log";
  const std::string command = std::string(HEADINGD_CANDUMP_FROM_CSV_BIN) + " --imu-csv " + HEADINGD_DEMO_IMU_CSV +
                              " --can-config " + test::configPath("can-headingd.toml") + " --out " + log_path +
                              " --mag-every 2 > " + dir.path() + "/stdout.txt";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const auto csv = files::readImuCsv(HEADINGD_DEMO_IMU_CSV);
  const CanSetup setup = loadCanSetup(test::configPath("can-headingd.toml"));
  const ImuFrameCodec codec(setup.config, setup.dbc);
  const ReplayResult r = replayLog(log_path, codec, epochSettingsFrom(setup.config));
  EXPECT_EQ(r.log.bad_lines, 0u);
  expectMatches(csv, r, 1'700'000'000'000'000'000LL, 2);
  // Bad configuration: non-zero exit and a message naming the file.
  const std::string bad = dir.write("bad.toml", "[can]\ndbc = \"nothing.dbc\"\n");
  const std::string bad_command = std::string(HEADINGD_CANDUMP_FROM_CSV_BIN) + " --imu-csv " + HEADINGD_DEMO_IMU_CSV +
                                  " --can-config " + bad + " --out " + log_path + " 2> " + dir.path() + "/stderr.txt";
  EXPECT_NE(std::system(bad_command.c_str()), 0);
  std::ifstream err(dir.path() + "/stderr.txt");
  const std::string message((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  EXPECT_NE(message.find("bad.toml:1: [can]: missing key 'gyro'"), std::string::npos) << message;
}
#endif

}  // namespace
}  // namespace headingd::can
