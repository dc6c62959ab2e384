// headingd-sim end to end: the real binary writing real files, byte-identical for a seed,
// its --help naming the conventions, and its exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class SimTool : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("headingd-sim-test-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs the tool with `args`; stdout and stderr go to files in the test's directory.
  int run(const std::string& args) {
    const std::string cmd = std::string("'") + HEADINGD_SIM_TOOL + "' " + args + " >'" + (dir_ / "stdout").string() +
                            "' 2>'" + (dir_ / "stderr").string() + "'";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string out() const { return slurp(dir_ / "stdout"); }
  std::string err() const { return slurp(dir_ / "stderr"); }

  fs::path dir_;
};

TEST_F(SimTool, WritesTheSameFilesForTheSameSeed) {
  const std::string common = " --scenario static-disturbed --rate-hz 50 --mount-yaw-deg 10 --decl-anomaly-deg 2";
  ASSERT_EQ(run("--seed 9 --out-dir '" + (dir_ / "a").string() + "'" + common), 0) << err();
  ASSERT_EQ(run("--seed 9 --out-dir '" + (dir_ / "b").string() + "'" + common), 0) << err();
  ASSERT_EQ(run("--seed 10 --out-dir '" + (dir_ / "c").string() + "'" + common), 0) << err();
  for (const char* file : {"imu.csv", "gps.nmea", "truth.csv", "gps_truth.csv", "sensor_errors.toml"}) {
    const std::string a = slurp(dir_ / "a" / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, slurp(dir_ / "b" / file)) << file;
  }
  EXPECT_NE(slurp(dir_ / "a" / "imu.csv"), slurp(dir_ / "c" / "imu.csv"));
  EXPECT_NE(slurp(dir_ / "a" / "gps.nmea"), slurp(dir_ / "c" / "gps.nmea"));
}

TEST_F(SimTool, HelpStatesTheConventionsAndListsTheScenarios) {
  ASSERT_EQ(run("--help"), 0);
  const std::string help = out();
  for (const char* text :
       {"TRUE attitude q_nb of the", "SENSOR, mapping sensor axes to NED", "12:00:00", "thesis-declination (244 s)",
        "urban-walk (600 s)", "static-disturbed (120 s)", "crawl (116 s)", "run (180 s)", "indoor-static (310 s)",
        "moving-disturbances (210 s)", "vehicle-ride (305 s)", "phone-texting (", "phone-calling (", "phone-swinging (",
        "phone-pocket (", "phone-running (", "phone-running-circles (", "phone (drawn per seed"}) {
    EXPECT_NE(help.find(text), std::string::npos) << text;
  }
}

TEST_F(SimTool, BadArgumentsExitWithTwo) {
  const std::string out_dir = " --out-dir '" + (dir_ / "x").string() + "'";
  EXPECT_EQ(run("--scenario nope --seed 1" + out_dir), 2);
  EXPECT_NE(err().find("unknown scenario"), std::string::npos) << err();
  EXPECT_EQ(run("--scenario crawl --seed 1 --date 2026-02-30" + out_dir), 2);
  EXPECT_EQ(run("--scenario crawl --seed 1 --gps-rate-hz 3" + out_dir), 2);
  EXPECT_EQ(run("--scenario crawl --seed 1 --imu-grade perfect" + out_dir), 2);
  EXPECT_EQ(run("--scenario crawl" + out_dir), 2);  // --seed is required
  EXPECT_FALSE(fs::exists(dir_ / "x"));
}

TEST_F(SimTool, PhoneGradeWritesItsTimingAndTheTrueGyroBias) {
  ASSERT_EQ(
      run("--scenario phone-pocket --seed 3 --imu-grade phone --rate-hz 50 --out-dir '" + (dir_ / "p").string() + "'"),
      0)
      << err();
  const std::string errors = slurp(dir_ / "p" / "sensor_errors.toml");
  for (const char* text : {"imu_grade = \"phone\"", "[timing]", "mag_rate_hz = ", "mag_lag_s = ", "accel_lag_s = "}) {
    EXPECT_NE(errors.find(text), std::string::npos) << text;
  }
  const std::string truth = slurp(dir_ / "p" / "truth.csv");
  EXPECT_NE(truth.substr(0, truth.find('\n')).find(",gyro_bias_x,gyro_bias_y,gyro_bias_z"), std::string::npos);
}

TEST_F(SimTool, UnwritableDirectoryExitsWithOne) {
  std::ofstream(dir_ / "file") << "x";
  EXPECT_EQ(run("--scenario crawl --seed 1 --rate-hz 10 --out-dir '" + (dir_ / "file" / "sub").string() + "'"), 1);
}

}  // namespace
