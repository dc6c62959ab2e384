// [gps] with source = "gpsd": defaults, and the messages for bad values.
#include <gtest/gtest.h>

#include "headingd/core/config_error.hpp"
#include "headingd/gpsd/gpsd_config.hpp"

namespace headingd::gpsd {
namespace {

GpsdConfig parse(const std::string& text) {
  const toml::table doc = toml::parse(text, std::string_view("test.toml"));
  return parseGpsdTable(doc["gps"].as_table(), "test.toml");
}

std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const core::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(GpsdConfig, DefaultsAreGpsdsLocalPort) {
  const GpsdConfig c = parse("[gps]\nsource = \"gpsd\"\n");
  EXPECT_EQ(c.host, "127.0.0.1");
  EXPECT_EQ(c.port, 2947u);
  const GpsdConfig d = parse("[gps]\nsource = \"gpsd\"\nhost = \"gps-box.local\"\nport = 12947\n");
  EXPECT_EQ(d.host, "gps-box.local");
  EXPECT_EQ(d.port, 12947u);
}

TEST(GpsdConfig, BadValuesNameTheLineAndKey) {
  EXPECT_NE(errorOf("[gps]\nsource = \"gpsd\"\nport = 70000\n").find("test.toml:3: [gps] port"), std::string::npos);
  EXPECT_NE(errorOf("[gps]\nsource = \"gpsd\"\nport = 0\n").find("[gps] port"), std::string::npos);
  EXPECT_NE(errorOf("[gps]\nsource = \"gpsd\"\nhost = \"\"\n").find("test.toml:3: [gps] host"), std::string::npos);
  EXPECT_NE(errorOf("[gps]\nsource = \"gpsd\"\nhost = \"a b\"\n").find("[gps] host"), std::string::npos);
  const std::string serial_key = errorOf("[gps]\nsource = \"gpsd\"\ndevice = \"/dev/ttyUSB0\"\n");
  EXPECT_NE(serial_key.find("device"), std::string::npos) << serial_key;
  EXPECT_NE(serial_key.find("source = \"serial\""), std::string::npos) << serial_key;
}

}  // namespace
}  // namespace headingd::gpsd
