#include "headingd/nmea/serial_gps_config.hpp"
#include "headingd/core/toml_document.hpp"

#include <array>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/nmea/gps_table_keys.hpp"

namespace headingd::nmea {
namespace {

using core::ConfigError;

constexpr std::array<std::uint32_t, 11> kBaudRates = {1200,  2400,   4800,   9600,   19200, 38400,
                                                      57600, 115200, 230400, 460800, 921600};

std::string baudList() {
  std::string s;
  for (const auto b : kBaudRates) s += (s.empty() ? "" : ", ") + std::to_string(b);
  return s;
}

}  // namespace

std::span<const std::uint32_t> standardBaudRates() { return kBaudRates; }

bool isStandardBaudRate(std::int64_t baud) {
  for (const auto b : kBaudRates) {
    if (baud == b) return true;
  }
  return false;
}

SerialGpsConfig parseGpsTable(const toml::table* gps, const std::string& source) {
  SerialGpsConfig c;
  core::TomlTableReader r(gps, source, "gps");
  c.enabled = r.boolean("enabled", c.enabled);
  // The daemon hands [gps] tables with source = "gpsd" to drivers/gpsd instead.
  r.choice("source", "serial", {"serial"});
  if (const toml::node* device = r.node("device")) {
    if (!device->is_string()) r.fail("device", "expected a string (the serial device path)");
    c.device = *device->value<std::string>();
    if (c.device.empty() || c.device.front() != '/') {
      r.fail("device", "expected an absolute path such as \"/dev/ttyUSB0\", got \"" + c.device + "\"");
    }
  }
  if (const toml::node* baud = r.node("baud")) {
    if (!baud->is_integer()) r.fail("baud", "expected an integer, one of " + baudList());
    const std::int64_t b = *baud->value<std::int64_t>();
    if (!isStandardBaudRate(b))
      r.fail("baud", std::to_string(b) + " is not a standard rate, expected one of " + baudList());
    c.baud = static_cast<unsigned>(b);
  }
  readSharedGpsKeys(r, c.reopen_backoff_initial_s, c.reopen_backoff_max_s, c.epoch_idle_s,
                    "config/gps.toml documents them");
  return c;
}

SerialGpsConfig parseGpsConfig(const toml::table& doc, const std::string& source) {
  return parseGpsTable(core::tableOf(doc, "gps", source), source);
}

SerialGpsConfig parseGpsConfigText(std::string_view toml_text, const std::string& source) {
  return parseGpsConfig(core::parseTomlDocument(toml_text, source), source);
}

}  // namespace headingd::nmea
