// The [gps] TOML loader: the shipped config/gps.toml, and every kind of bad configuration
// stopped with the file, the line, the key and what was expected.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "headingd/core/params_toml.hpp"
#include "headingd/nmea/serial_gps_config.hpp"

namespace headingd::nmea {
namespace {

std::string readText(const char* path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The message of the ConfigError that parsing text throws ("" if none).
std::string errorOf(const std::string& text) {
  try {
    parseGpsConfigText(text, "test.toml");
  } catch (const core::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(GpsConfig, ShippedExampleSetsEveryKeyToItsDefault) {
  const std::string text = readText(HEADINGD_GPS_TOML);
  ASSERT_FALSE(text.empty());
  const SerialGpsConfig parsed = parseGpsConfigText(text, "config/gps.toml");
  const SerialGpsConfig defaults;
  EXPECT_EQ(parsed.enabled, defaults.enabled);
  EXPECT_EQ(parsed.device, defaults.device);
  EXPECT_EQ(parsed.baud, defaults.baud);
  EXPECT_EQ(parsed.reopen_backoff_initial_s, defaults.reopen_backoff_initial_s);
  EXPECT_EQ(parsed.reopen_backoff_max_s, defaults.reopen_backoff_max_s);
  EXPECT_EQ(parsed.epoch_idle_s, defaults.epoch_idle_s);
  // Every key is written out (commented examples do not count).
  for (const char* key :
       {"enabled", "device", "baud", "reopen_backoff_initial_s", "reopen_backoff_max_s", "epoch_idle_s"}) {
    EXPECT_NE(text.find(std::string("\n") + key + " = "), std::string::npos) << key;
  }
}

TEST(GpsConfig, ReadsEveryKey) {
  const auto c = parseGpsConfigText(
      "[estimator]\ngyro_noise_rad_s = 1.0\n"  // other tables are not the loader's business
      "[gps]\nenabled = false\ndevice = \"/dev/gps0\"\nbaud = 4800\nreopen_backoff_initial_s = 1\n"
      "reopen_backoff_max_s = 30.0\nepoch_idle_s = 0\n",
      "t.toml");
  EXPECT_FALSE(c.enabled);
  EXPECT_EQ(c.device, "/dev/gps0");
  EXPECT_EQ(c.baud, 4800u);
  EXPECT_EQ(c.reopen_backoff_initial_s, 1.0);
  EXPECT_EQ(c.reopen_backoff_max_s, 30.0);
  EXPECT_EQ(c.epoch_idle_s, 0.0);
}

TEST(GpsConfig, MissingTableGivesDefaults) {
  const auto c = parseGpsConfigText("[can]\ninterface = \"can0\"\n", "t.toml");
  EXPECT_EQ(c.device, SerialGpsConfig{}.device);
}

TEST(GpsConfig, BadValuesNameFileLineKeyAndWhatWasExpected) {
  EXPECT_EQ(errorOf("[gps]\nbaud = 9601\n"),
            "test.toml:2: [gps] baud: 9601 is not a standard rate, expected one of 1200, 2400, 4800, 9600, 19200, "
            "38400, 57600, 115200, 230400, 460800, 921600");
  EXPECT_EQ(errorOf("[gps]\n\nbaud = \"9600\"\n"),
            "test.toml:3: [gps] baud: expected an integer, one of 1200, 2400, 4800, 9600, 19200, 38400, 57600, "
            "115200, 230400, 460800, 921600");
  EXPECT_EQ(errorOf("[gps]\nenabled = 1\n"), "test.toml:2: [gps] enabled: expected true or false");
  EXPECT_EQ(errorOf("[gps]\ndevice = 5\n"), "test.toml:2: [gps] device: expected a string (the serial device path)");
  EXPECT_EQ(errorOf("[gps]\ndevice = \"ttyUSB0\"\n"),
            "test.toml:2: [gps] device: expected an absolute path such as \"/dev/ttyUSB0\", got \"ttyUSB0\"");
  EXPECT_EQ(errorOf("[gps]\nreopen_backoff_initial_s = 0\n"),
            "test.toml:2: [gps] reopen_backoff_initial_s: 0 is out of range, expected 0.01 .. 60 s");
  EXPECT_EQ(errorOf("[gps]\nepoch_idle_s = true\n"), "test.toml:2: [gps] epoch_idle_s: expected a number in s");
  EXPECT_EQ(errorOf("[gps]\nbaudrate = 9600\n"),
            "test.toml:2: [gps] baudrate: unknown key (expected one of: enabled, source, device, baud, "
            "reopen_backoff_initial_s, reopen_backoff_max_s, epoch_idle_s; config/gps.toml documents them)");
  EXPECT_EQ(
      errorOf("[gps]\nreopen_backoff_initial_s = 2\nreopen_backoff_max_s = 1\n"),
      "test.toml:3: [gps] reopen_backoff_max_s: 1 is below reopen_backoff_initial_s (2), expected max >= initial");
  EXPECT_EQ(errorOf("gps = 3\n"), "test.toml:1: 'gps' must be a table ([gps])");
  const std::string syntax = errorOf("[gps]\ndevice = \"/dev/gps0\n");
  EXPECT_EQ(syntax.rfind("test.toml:2: TOML syntax error: ", 0), 0u) << syntax;
}

TEST(GpsConfig, StandardBaudRates) {
  for (const std::int64_t b : {1200, 4800, 9600, 38400, 115200, 921600}) EXPECT_TRUE(isStandardBaudRate(b)) << b;
  for (const std::int64_t b : {0, -9600, 9601, 14400, 250000, 1000000}) EXPECT_FALSE(isStandardBaudRate(b)) << b;
}

}  // namespace
}  // namespace headingd::nmea
