#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "headingd/can/can_config_toml.hpp"
#include "headingd/core/toml_document.hpp"

namespace headingd::can {
namespace {

std::string at(const std::string& source, const toml::node& node, std::string_view key) {
  return source + ":" + std::to_string(node.source().begin.line) + ": [can] " + std::string(key);
}

bool isIdentifier(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s.front())) != 0) return false;
  for (char ch : s) {
    if (std::isalnum(static_cast<unsigned char>(ch)) == 0 && ch != '_') return false;
  }
  return true;
}

SignalRef parseSignalRef(const toml::node& node, const std::string& where_key) {
  const std::optional<std::string> text = node.value<std::string>();
  if (!text || !node.is_string()) throw ConfigError(where_key + ": expected a string \"Message.Signal\"");
  SignalRef ref;
  ref.line = static_cast<int>(node.source().begin.line);
  std::string_view s = *text;
  if (!s.empty() && s.front() == '-') {
    ref.negate = true;
    s.remove_prefix(1);
  }
  const std::size_t dot = s.find('.');
  if (dot == std::string_view::npos || !isIdentifier(s.substr(0, dot)) || !isIdentifier(s.substr(dot + 1))) {
    throw ConfigError(where_key + ": '" + *text +
                      "' is not a signal reference, expected \"Message.Signal\" or \"-Message.Signal\" (DBC names)");
  }
  ref.message = std::string(s.substr(0, dot));
  ref.signal = std::string(s.substr(dot + 1));
  return ref;
}

std::array<SignalRef, 3> parseAxes(const toml::node& node, const std::string& where_key) {
  const toml::array* arr = node.as_array();
  if (arr == nullptr || arr->size() != 3) {
    throw ConfigError(where_key + ": expected an array of 3 signals [x, y, z], e.g. [\"Msg.X\", \"Msg.Y\", \"-Msg.Z\"]");
  }
  std::array<SignalRef, 3> axes;
  for (std::size_t i = 0; i < 3; ++i) axes[i] = parseSignalRef(*arr->get(i), where_key);
  return axes;
}

double parseNumber(const toml::node& node, const std::string& where_key, double min, double max, const char* unit) {
  const std::optional<double> v = node.value<double>();
  if (!v || !(node.is_floating_point() || node.is_integer())) {
    throw ConfigError(where_key + ": expected a number in " + unit);
  }
  if (!(*v >= min && *v <= max)) {
    std::ostringstream o;
    o << where_key << ": " << *v << " is out of range, expected " << min << " .. " << max << " " << unit;
    throw ConfigError(o.str());
  }
  return *v;
}

double parseUnitFactor(const toml::node& node, const std::string& where_key, const char* si) {
  const double v = parseNumber(node, where_key, -1e9, 1e9, (std::string("(") + si + " per DBC unit)").c_str());
  if (v == 0.0) throw ConfigError(where_key + ": expected a non-zero factor (" + si + " per DBC unit)");
  return v;
}

bool parseBool(const toml::node& node, const std::string& where_key) {
  if (!node.is_boolean()) throw ConfigError(where_key + ": expected true or false");
  return *node.value<bool>();
}

std::string parseString(const toml::node& node, const std::string& where_key, const char* what) {
  if (!node.is_string() || node.value<std::string>()->empty()) {
    throw ConfigError(where_key + ": expected " + std::string(what));
  }
  return *node.value<std::string>();
}

// Every key of [can]. A key is read below only if it is listed here, so this list (which
// the error for an unknown key prints, and tests/package compares with headingd.toml(5))
// cannot miss one.
constexpr const char* kCanKeys[] = {"interface",         "dbc",
                                    "j1939",             "gyro",
                                    "accel",             "mag",
                                    "sequence",          "gyro_unit_factor",
                                    "accel_unit_factor", "mag_unit_factor",
                                    "epoch_window_s",    "epoch_waits_for_mag",
                                    "reconnect_initial_s", "reconnect_max_s",
                                    "receive_buffer_bytes"};

bool isCanKey(const std::string& key) {
  for (const char* k : kCanKeys) {
    if (key == k) return true;
  }
  return false;
}

[[noreturn]] void unknownCanKey(const std::string& where) {
  std::string list;
  for (const char* k : kCanKeys) list += (list.empty() ? "" : ", ") + std::string(k);
  throw ConfigError(where + ": unknown key (expected one of: " + list + "; config/can-headingd.toml documents them)");
}

}  // namespace

int CanConfig::lineOf(const std::string& key) const {
  const auto it = key_lines.find(key);
  return it == key_lines.end() ? 0 : it->second;
}

std::string CanConfig::where(const std::string& key) const {
  return source + ":" + std::to_string(lineOf(key)) + ": [can] " + key;
}

CanConfig parseCanTable(const toml::table& table, const std::string& source, const std::string& config_dir) {
  CanConfig c;
  c.source = source;
  std::string dbc;
  for (auto&& [key_node, node] : table) {
    const std::string key(key_node.str());
    const std::string w = at(source, node, key);
    c.key_lines[key] = static_cast<int>(node.source().begin.line);
    if (!isCanKey(key)) unknownCanKey(w);
    if (key == "interface") {
      c.interface = parseString(node, w, "a network interface name such as \"can0\"");
      if (c.interface.size() >= 16) throw ConfigError(w + ": expected an interface name of at most 15 characters");
    } else if (key == "dbc") {
      dbc = parseString(node, w, "the path of a DBC file (relative to this file)");
    } else if (key == "j1939") {
      c.j1939 = parseBool(node, w);
    } else if (key == "gyro") {
      c.gyro = parseAxes(node, w);
    } else if (key == "accel") {
      c.accel = parseAxes(node, w);
    } else if (key == "mag") {
      c.mag = parseAxes(node, w);
    } else if (key == "sequence") {
      const toml::array* arr = node.as_array();
      if (arr == nullptr || arr->empty()) throw ConfigError(w + ": expected an array of counter signals [\"Msg.Seq\", ...]");
      for (const auto& element : *arr) c.sequence.push_back(parseSignalRef(element, w));
    } else if (key == "gyro_unit_factor") {
      c.gyro_unit_factor = parseUnitFactor(node, w, "rad/s");
    } else if (key == "accel_unit_factor") {
      c.accel_unit_factor = parseUnitFactor(node, w, "m/s^2");
    } else if (key == "mag_unit_factor") {
      c.mag_unit_factor = parseUnitFactor(node, w, "uT");
    } else if (key == "epoch_window_s") {
      c.epoch_window_s = parseNumber(node, w, 1e-5, 1.0, "s");
    } else if (key == "epoch_waits_for_mag") {
      c.epoch_waits_for_mag = parseBool(node, w);
    } else if (key == "reconnect_initial_s") {
      c.reconnect_initial_s = parseNumber(node, w, 0.001, 60.0, "s");
    } else if (key == "reconnect_max_s") {
      c.reconnect_max_s = parseNumber(node, w, 0.001, 3600.0, "s");
    } else if (key == "receive_buffer_bytes") {
      if (!node.is_integer()) throw ConfigError(w + ": expected an integer number of bytes");
      c.receive_buffer_bytes = static_cast<int>(parseNumber(node, w, 4096, 64.0 * 1024 * 1024, "bytes"));
    } else {
      unknownCanKey(w);  // listed in kCanKeys but not read: a key without its parser
    }
  }
  const std::string table_line = source + ":" + std::to_string(table.source().begin.line) + ": [can]";
  if (dbc.empty()) throw ConfigError(table_line + ": missing key 'dbc' (the DBC file describing the IMU frames)");
  if (!c.key_lines.contains("gyro")) throw ConfigError(table_line + ": missing key 'gyro' ([x, y, z] signals)");
  if (!c.key_lines.contains("accel")) throw ConfigError(table_line + ": missing key 'accel' ([x, y, z] signals)");
  if (c.reconnect_max_s < c.reconnect_initial_s) {
    throw ConfigError(c.where("reconnect_max_s") + ": expected a value >= reconnect_initial_s (" +
                      std::to_string(c.reconnect_initial_s) + ")");
  }
  if (c.mag_unit_factor && !c.mag) throw ConfigError(c.where("mag_unit_factor") + ": given without 'mag' signals");
  const std::filesystem::path dbc_path(dbc);
  c.dbc_path = dbc_path.is_absolute() || config_dir.empty() ? dbc_path.string()
                                                            : (std::filesystem::path(config_dir) / dbc_path).string();
  return c;
}

CanConfig parseCanConfig(std::string_view toml_text, const std::string& source, const std::string& config_dir) {
  toml::table doc = core::parseTomlDocument(toml_text, source);
  const toml::node* can = doc.get("can");
  if (can == nullptr) throw ConfigError(source + ": missing table [can]");
  if (!can->is_table()) {
    throw ConfigError(source + ":" + std::to_string(can->source().begin.line) + ": 'can' must be a table ([can])");
  }
  return parseCanTable(*can->as_table(), source, config_dir);
}

CanConfig loadCanConfigFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open the configuration file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseCanConfig(text.str(), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace headingd::can
