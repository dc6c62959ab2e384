#include "toml_table_reader.hpp"

#include <fstream>
#include <sstream>

namespace headingd::daemon {

std::string sourceLine(const std::string& source, const toml::node& node) {
  return source + ":" + std::to_string(node.source().begin.line);
}

TomlTableReader::TomlTableReader(const toml::table* table, std::string source, std::string table_name)
    : table_(table), source_(std::move(source)), table_name_(std::move(table_name)) {}

const toml::node* TomlTableReader::find(std::string_view key) {
  known_.emplace(key);
  return table_ == nullptr ? nullptr : table_->get(key);
}

std::string TomlTableReader::where(std::string_view key) const {
  const toml::node* node = table_ == nullptr ? nullptr : table_->get(key);
  const std::string at = node != nullptr ? sourceLine(source_, *node) : source_;
  return at + ": [" + table_name_ + "] " + std::string(key);
}

void TomlTableReader::fail(std::string_view key, const std::string& what) const {
  throw core::ConfigError(where(key) + ": " + what);
}

double TomlTableReader::number(std::string_view key, double fallback, double min, double max, const char* unit) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  const std::optional<double> value = node->value<double>();
  if (!value || !(node->is_floating_point() || node->is_integer())) fail(key, std::string("expected a number in ") + unit);
  if (!(*value >= min && *value <= max)) {
    std::ostringstream o;
    o << *value << " is out of range, expected " << min << " .. " << max << " " << unit;
    fail(key, o.str());
  }
  return *value;
}

std::int64_t TomlTableReader::integer(std::string_view key, std::int64_t fallback, std::int64_t min,
                                      std::int64_t max) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  if (!node->is_integer()) fail(key, "expected an integer");
  const std::int64_t value = *node->value<std::int64_t>();
  if (value < min || value > max) {
    fail(key, std::to_string(value) + " is out of range, expected an integer " + std::to_string(min) + " .. " +
                  std::to_string(max));
  }
  return value;
}

bool TomlTableReader::boolean(std::string_view key, bool fallback) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  if (!node->is_boolean()) fail(key, "expected true or false");
  return *node->value<bool>();
}

std::string TomlTableReader::string(std::string_view key, const std::string& fallback) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  if (!node->is_string()) fail(key, "expected a string in quotes");
  return *node->value<std::string>();
}

std::string TomlTableReader::choice(std::string_view key, const std::string& fallback,
                                    std::initializer_list<const char*> choices) {
  std::string expected;
  for (const char* c : choices) expected += (expected.empty() ? "\"" : ", \"") + std::string(c) + "\"";
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  if (!node->is_string()) fail(key, "expected one of " + expected);
  const std::string value = *node->value<std::string>();
  for (const char* c : choices) {
    if (value == c) return value;
  }
  fail(key, "'" + value + "' is not one of " + expected);
}

std::vector<std::int64_t> TomlTableReader::integerArray(std::string_view key, std::int64_t min, std::int64_t max) {
  const toml::node* node = find(key);
  std::vector<std::int64_t> values;
  if (node == nullptr) return values;
  const std::string expected =
      "expected an array of integers " + std::to_string(min) + " .. " + std::to_string(max) + ", e.g. [2, 3]";
  const toml::array* array = node->as_array();
  if (array == nullptr) fail(key, expected);
  for (const toml::node& element : *array) {
    if (!element.is_integer()) fail(key, expected);
    const std::int64_t v = *element.value<std::int64_t>();
    if (v < min || v > max) fail(key, std::to_string(v) + " is out of range, " + expected);
    values.push_back(v);
  }
  return values;
}

std::string TomlTableReader::path(std::string_view key, const std::string& fallback, const std::string& base_dir,
                                  bool must_exist) {
  std::string value = string(key, fallback);
  if (value.empty()) return value;
  if (value.front() != '/' && !base_dir.empty()) value = base_dir + "/" + value;
  if (must_exist && !std::ifstream(value).good()) fail(key, "cannot open '" + value + "' for reading");
  return value;
}

void TomlTableReader::rejectUnknownKeys() const {
  if (table_ == nullptr) return;
  for (auto&& [key, node] : *table_) {
    if (known_.count(key.str()) == 0) {
      std::string list;
      for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
      throw core::ConfigError(sourceLine(source_, node) + ": [" + table_name_ + "] " + std::string(key.str()) +
                              ": unknown key (expected one of: " + list + ")");
    }
  }
}

}  // namespace headingd::daemon
