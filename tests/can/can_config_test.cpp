// The [can] table: shipped examples load, every error names file:line, key and expectation.
#include <gtest/gtest.h>

#include "can_test_support.hpp"
#include "headingd/can/imu_frame_codec.hpp"

namespace headingd::can {
namespace {

using test::TempDir;

constexpr const char* kDbc = R"(BO_ 288 GYRO: 8 IMU
 SG_ X : 0|16@1- (0.01,0) [0|0] "deg/s" R
 SG_ Y : 16|16@1- (0.01,0) [0|0] "deg/s" R
 SG_ Z : 32|16@1- (0.01,0) [0|0] "deg/s" R
 SG_ Seq : 56|8@1+ (1,0) [0|0] "" R
 SG_ Odd : 48|8@1- (1,0) [0|0] "furlong" R
BO_ 289 ACC: 8 IMU
 SG_ X : 0|16@1- (1,0) [0|0] "mg" R
 SG_ Y : 16|16@1- (1,0) [0|0] "mg" R
 SG_ Z : 32|16@1- (1,0) [0|0] "mg" R
 SG_ Seq : 56|4@1+ (1,0) [0|0] "" R
)";

CanSetup setupFrom(const TempDir& dir, const std::string& can_table) {
  dir.write("imu.dbc", kDbc);
  const std::string path = dir.write("c.toml", "[other]\nx = 1\n\n" + can_table);
  CanSetup setup = loadCanSetup(path);
  ImuFrameCodec codec(setup.config, setup.dbc);  // resolve now, as the daemon does
  return setup;
}

void expectConfigError(const std::string& can_table, const std::string& fragment) {
  TempDir dir;
  try {
    setupFrom(dir, can_table);
    ADD_FAILURE() << "no error for:\n" << can_table;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

const std::string kGood =
    "[can]\ndbc = \"imu.dbc\"\ngyro = [\"GYRO.X\", \"-GYRO.Y\", \"GYRO.Z\"]\naccel = [\"ACC.X\", \"ACC.Y\", "
    "\"ACC.Z\"]\n";

TEST(CanConfig, ShippedExamplesLoadAndResolve) {
  for (const char* name : {"can-headingd.toml", "can-openimu.toml"}) {
    const CanSetup setup = loadCanSetup(test::configPath(name));
    const ImuFrameCodec codec(setup.config, setup.dbc);
    EXPECT_TRUE(codec.hasMag()) << name;
    EXPECT_EQ(codec.messages().size(), 3u) << name;
  }
  const CanSetup own = loadCanSetup(test::configPath("can-headingd.toml"));
  EXPECT_EQ(ImuFrameCodec(own.config, own.dbc).sequenceBits(), 4u);
  EXPECT_TRUE(loadCanSetup(test::configPath("can-openimu.toml")).config.j1939);
}

TEST(CanConfig, DefaultsAndRelativeDbcPath) {
  TempDir dir;
  const CanSetup s = setupFrom(dir, kGood);
  EXPECT_EQ(s.config.interface, "can0");
  EXPECT_EQ(s.config.dbc_path, dir.path() + "/imu.dbc");
  EXPECT_FALSE(s.config.j1939);
  EXPECT_TRUE(s.config.gyro[1].negate);
  EXPECT_EQ(s.config.gyro[1].line, 6);
  EXPECT_DOUBLE_EQ(s.config.epoch_window_s, 0.002);
}

TEST(CanConfig, ErrorsNameFileLineKey) {
  expectConfigError("[can]\ndbc = \"imu.dbc\"\nbogus = 1\n", "c.toml:6: [can] bogus: unknown key");
  expectConfigError("[can]\ngyro = [\"GYRO.X\", \"GYRO.Y\", \"GYRO.Z\"]\n", "c.toml:4: [can]: missing key 'dbc'");
  expectConfigError(kGood + "epoch_window_s = 5\n",
                    "c.toml:8: [can] epoch_window_s: 5 is out of range, expected 1e-05 .. 1 s");
  expectConfigError(kGood + "j1939 = \"yes\"\n", "c.toml:8: [can] j1939: expected true or false");
  expectConfigError("[can]\ndbc = \"imu.dbc\"\ngyro = [\"GYRO.X\", \"GYRO.Y\"]\n",
                    "c.toml:6: [can] gyro: expected an array of 3 signals");
  expectConfigError("[can]\ndbc = \"imu.dbc\"\ngyro = [\"GYRO\", \"GYRO.Y\", \"GYRO.Z\"]\n",
                    "'GYRO' is not a signal reference");
  expectConfigError(kGood + "mag = [\"MAG.X\", \"MAG.Y\", \"MAG.Z\"]\n",
                    "c.toml:8: [can] mag: 'MAG.X': expected a message (BO_) of");
  expectConfigError(kGood + "mag = [\"GYRO.Odd\", \"GYRO.Odd\", \"GYRO.Odd\"]\n",
                    "c.toml:8: [can] mag: 'GYRO.Odd': unit \"furlong\"");
  expectConfigError(
      "[can]\ndbc = \"imu.dbc\"\ngyro = [\"GYRO.X\", \"GYRO.Y\", \"GYRO.W\"]\naccel = [\"ACC.X\", \"ACC.Y\", "
      "\"ACC.Z\"]\n",
      "c.toml:6: [can] gyro: 'GYRO.W': expected a signal (SG_) of message GYRO");
  expectConfigError(kGood + "j1939 = true\n", "j1939 = true expects 29-bit ids");
  expectConfigError(kGood + "sequence = [\"GYRO.Seq\", \"ACC.Seq\"]\n",
                    "expected the same width as the other counters (8 bits)");
  expectConfigError(kGood + "reconnect_initial_s = 2\nreconnect_max_s = 1\n",
                    "c.toml:9: [can] reconnect_max_s: expected a value >= reconnect_initial_s");
  expectConfigError(
      "[can]\ndbc = \"missing.dbc\"\ngyro = [\"GYRO.X\", \"GYRO.Y\", \"GYRO.Z\"]\naccel = [\"ACC.X\", \"ACC.Y\", "
      "\"ACC.Z\"]\n",
      "c.toml:5: [can] dbc: expected a readable DBC file");
  expectConfigError("[can]\ndbc = 3\n", "c.toml:5: [can] dbc: expected the path of a DBC file");
  expectConfigError("[can\n", "c.toml:4: TOML syntax error");
  expectConfigError(kGood + "gyro_unit_factor = 0\n", "c.toml:8: [can] gyro_unit_factor: expected a non-zero factor");
}

TEST(CanConfig, ExplicitFactorOverridesUnknownUnit) {
  TempDir dir;
  const CanSetup s = setupFrom(dir, kGood + "mag = [\"GYRO.Odd\", \"ACC.Seq\", \"GYRO.Seq\"]\nmag_unit_factor = 0.5\n");
  EXPECT_DOUBLE_EQ(*s.config.mag_unit_factor, 0.5);
}

TEST(CanConfig, MissingCanTable) {
  EXPECT_THROW(parseCanConfig("[estimator]\n", "x.toml", ""), ConfigError);
  EXPECT_THROW(loadCanConfigFile("/nonexistent/c.toml"), ConfigError);
}

}  // namespace
}  // namespace headingd::can
