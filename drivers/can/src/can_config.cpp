#include <cmath>
#include <filesystem>

#include "headingd/can/can_config_toml.hpp"
#include "headingd/core/toml_document.hpp"
#include "headingd/core/toml_table_reader.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::can {
namespace {

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
    throw ConfigError(where_key +
                      ": expected an array of 3 signals [x, y, z], e.g. [\"Msg.X\", \"Msg.Y\", \"-Msg.Z\"]");
  }
  std::array<SignalRef, 3> axes;
  for (std::size_t i = 0; i < 3; ++i) axes[i] = parseSignalRef(*arr->get(i), where_key);
  return axes;
}

std::string parseString(const toml::node& node, const std::string& where_key, const char* what) {
  if (!node.is_string() || node.value<std::string>()->empty()) {
    throw ConfigError(where_key + ": expected " + std::string(what));
  }
  return *node.value<std::string>();
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
  // Checks after parsing (the DBC's signals, the counters) name the line of their key.
  for (auto&& [key, node] : table) c.key_lines[std::string(key.str())] = static_cast<int>(node.source().begin.line);
  core::TomlTableReader r(&table, source, "can");
  if (const toml::node* node = r.node("interface")) {
    c.interface = parseString(*node, r.where("interface"), "a network interface name such as \"can0\"");
    if (c.interface.size() >= 16) r.fail("interface", "expected an interface name of at most 15 characters");
  }
  std::string dbc;
  if (const toml::node* node = r.node("dbc")) {
    dbc = parseString(*node, r.where("dbc"), "the path of a DBC file (relative to this file)");
  }
  c.j1939 = r.boolean("j1939", c.j1939);
  for (auto [key, axes] : {std::pair{"gyro", &c.gyro}, std::pair{"accel", &c.accel}}) {
    if (const toml::node* node = r.node(key)) *axes = parseAxes(*node, r.where(key));
  }
  if (const toml::node* node = r.node("mag")) c.mag = parseAxes(*node, r.where("mag"));
  if (const toml::node* node = r.node("sequence")) {
    const toml::array* arr = node->as_array();
    if (arr == nullptr || arr->empty()) r.fail("sequence", "expected an array of counter signals [\"Msg.Seq\", ...]");
    for (const auto& element : *arr) c.sequence.push_back(parseSignalRef(element, r.where("sequence")));
  }
  // value * factor = the SI unit; overrides the DBC's unit.
  const auto unitFactor = [&r](const char* key, const char* si) -> std::optional<double> {
    if (!r.has(key)) return std::nullopt;
    const std::string unit = std::string("(") + si + " per DBC unit)";
    const double v = r.number(key, 0.0, -1e9, 1e9, unit.c_str());
    if (v == 0.0) r.fail(key, "expected a non-zero factor " + unit);
    return v;
  };
  c.gyro_unit_factor = unitFactor("gyro_unit_factor", "rad/s");
  c.accel_unit_factor = unitFactor("accel_unit_factor", "m/s^2");
  c.mag_unit_factor = unitFactor("mag_unit_factor", "uT");
  c.epoch_window_s = r.number("epoch_window_s", c.epoch_window_s, 1e-5, 1.0, "s");
  c.epoch_waits_for_mag = r.boolean("epoch_waits_for_mag", c.epoch_waits_for_mag);
  c.reconnect_initial_s = r.number("reconnect_initial_s", c.reconnect_initial_s, 0.001, 60.0, "s");
  c.reconnect_max_s = r.number("reconnect_max_s", c.reconnect_max_s, 0.001, 3600.0, "s");
  c.receive_buffer_bytes =
      static_cast<int>(r.integer("receive_buffer_bytes", c.receive_buffer_bytes, 4096, 64 * 1024 * 1024));
  r.rejectUnknownKeys("config/can-headingd.toml documents them");

  const std::string table_line = source + ":" + std::to_string(table.source().begin.line) + ": [can]";
  if (dbc.empty()) throw ConfigError(table_line + ": missing key 'dbc' (the DBC file describing the IMU frames)");
  if (!c.key_lines.contains("gyro")) throw ConfigError(table_line + ": missing key 'gyro' ([x, y, z] signals)");
  if (!c.key_lines.contains("accel")) throw ConfigError(table_line + ": missing key 'accel' ([x, y, z] signals)");
  if (c.reconnect_max_s < c.reconnect_initial_s) {
    r.fail("reconnect_max_s",
           "expected a value >= reconnect_initial_s (" + std::to_string(c.reconnect_initial_s) + ")");
  }
  if (c.mag_unit_factor && !c.mag) r.fail("mag_unit_factor", "given without 'mag' signals");
  const std::filesystem::path dbc_path(dbc);
  c.dbc_path = dbc_path.is_absolute() || config_dir.empty() ? dbc_path.string()
                                                            : (std::filesystem::path(config_dir) / dbc_path).string();
  return c;
}

CanConfig parseCanConfig(std::string_view toml_text, const std::string& source, const std::string& config_dir) {
  const toml::table doc = core::parseTomlDocument(toml_text, source);
  const toml::table* can = core::tableOf(doc, "can", source);
  if (can == nullptr) throw ConfigError(source + ": missing table [can]");
  return parseCanTable(*can, source, config_dir);
}

CanConfig loadCanConfigFile(const std::string& path) {
  std::string text;
  try {
    text = files::readWholeFile(path, files::kConfigFileLimit);
  } catch (const files::FileError& e) {
    throw ConfigError(std::string(e.what()) + " (the configuration file)");
  }
  return parseCanConfig(text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace headingd::can
