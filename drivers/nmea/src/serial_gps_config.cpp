#include "headingd/nmea/serial_gps_config.hpp"
#include "headingd/core/toml_document.hpp"

#include <array>
#include <sstream>

#include "headingd/core/params_toml.hpp"

namespace headingd::nmea {
namespace {

using core::ConfigError;

constexpr std::array<std::uint32_t, 11> kBaudRates = {1200,  2400,  4800,   9600,   19200, 38400,
                                                      57600, 115200, 230400, 460800, 921600};

std::string at(const std::string& source, const toml::node& node, std::string_view key) {
  std::ostringstream o;
  o << source << ":" << node.source().begin.line << ": [gps] " << key;
  return o.str();
}

double seconds(const toml::node& node, const std::string& where, double min, double max) {
  if (!(node.is_floating_point() || node.is_integer())) throw ConfigError(where + ": expected a number in s");
  const double v = *node.value<double>();
  if (!(v >= min && v <= max)) {
    std::ostringstream o;
    o << where << ": " << v << " is out of range, expected " << min << " .. " << max << " s";
    throw ConfigError(o.str());
  }
  return v;
}

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

SerialGpsConfig parseGpsConfig(const toml::table& doc, const std::string& source) {
  SerialGpsConfig c;
  const toml::node* gps_node = doc.get("gps");
  if (gps_node == nullptr) return c;
  const toml::table* gps = gps_node->as_table();
  if (gps == nullptr) {
    throw ConfigError(source + ":" + std::to_string(gps_node->source().begin.line) + ": 'gps' must be a table ([gps])");
  }
  // Which line set each back-off key, to name it in the cross-check below.
  const toml::node* backoff_max_node = nullptr;
  for (auto&& [key_name, node] : *gps) {
    const std::string_view key = key_name.str();
    const std::string where = at(source, node, key);
    if (key == "enabled") {
      if (!node.is_boolean()) throw ConfigError(where + ": expected true or false");
      c.enabled = *node.value<bool>();
    } else if (key == "device") {
      if (!node.is_string()) throw ConfigError(where + ": expected a string (the serial device path)");
      c.device = *node.value<std::string>();
      if (c.device.empty() || c.device.front() != '/') {
        throw ConfigError(where + ": expected an absolute path such as \"/dev/ttyUSB0\", got \"" + c.device + "\"");
      }
    } else if (key == "baud") {
      if (!node.is_integer()) throw ConfigError(where + ": expected an integer, one of " + baudList());
      const std::int64_t b = *node.value<std::int64_t>();
      if (!isStandardBaudRate(b)) {
        throw ConfigError(where + ": " + std::to_string(b) + " is not a standard rate, expected one of " + baudList());
      }
      c.baud = static_cast<unsigned>(b);
    } else if (key == "reopen_backoff_initial_s") {
      c.reopen_backoff_initial_s = seconds(node, where, 0.01, 60.0);
    } else if (key == "reopen_backoff_max_s") {
      c.reopen_backoff_max_s = seconds(node, where, 0.01, 600.0);
      backoff_max_node = &node;
    } else if (key == "epoch_idle_s") {
      c.epoch_idle_s = seconds(node, where, 0.0, 10.0);
    } else {
      throw ConfigError(where + ": unknown key (expected enabled, device, baud, reopen_backoff_initial_s, "
                                "reopen_backoff_max_s, epoch_idle_s; see config/gps.toml)");
    }
  }
  if (c.reopen_backoff_max_s < c.reopen_backoff_initial_s) {
    const toml::node& n = backoff_max_node != nullptr ? *backoff_max_node : *gps_node;
    std::ostringstream o;
    o << at(source, n, "reopen_backoff_max_s") << ": " << c.reopen_backoff_max_s
      << " is below reopen_backoff_initial_s (" << c.reopen_backoff_initial_s << "), expected max >= initial";
    throw ConfigError(o.str());
  }
  return c;
}

SerialGpsConfig parseGpsConfigText(std::string_view toml_text, const std::string& source) {
  return parseGpsConfig(core::parseTomlDocument(toml_text, source), source);
}

}  // namespace headingd::nmea
