#include "headingd/core/toml_table_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace headingd::core {
namespace {

// A finite number (integers count), or nothing.
std::optional<double> finiteValue(const toml::node& node) {
  if (!(node.is_floating_point() || node.is_integer())) return std::nullopt;
  const double v = *node.value<double>();
  if (!std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

std::string sourceLine(const std::string& source, const toml::node& node) {
  return source + ":" + std::to_string(node.source().begin.line);
}

const toml::table* tableOf(const toml::table& doc, std::string_view name, const std::string& source) {
  const toml::node* node = doc.get(name);
  if (node == nullptr) return nullptr;
  if (!node->is_table()) {
    throw ConfigError(sourceLine(source, *node) + ": '" + std::string(name) + "' must be a table ([" +
                      std::string(name) + "])");
  }
  return node->as_table();
}

void rejectUnknownTables(const toml::table& doc, const std::string& source, std::initializer_list<const char*> names) {
  rejectUnknownTables(doc, source, std::vector<std::string>(names.begin(), names.end()));
}

void rejectUnknownTables(const toml::table& doc, const std::string& source, const std::vector<std::string>& names) {
  std::string expected;
  for (const std::string& t : names) expected += (expected.empty() ? "[" : ", [") + t + "]";
  for (auto&& [key, node] : doc) {
    // A copy of the binding's name for the lambda: clang before 16 cannot capture bindings.
    const std::string_view name = key.str();
    const bool known = std::any_of(names.begin(), names.end(), [&](const std::string& t) { return name == t; });
    if (!known) {
      throw ConfigError(sourceLine(source, node) + ": unknown table or key '" + std::string(key.str()) +
                        "' (expected " + expected + ")");
    }
    tableOf(doc, key.str(), source);
  }
}

TomlTableReader::TomlTableReader(const toml::table* table, std::string source, std::string table_name)
    : table_(table), source_(std::move(source)), table_name_(std::move(table_name)) {}

const toml::node* TomlTableReader::find(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
  return table_ == nullptr ? nullptr : table_->get(key);
}

bool TomlTableReader::has(std::string_view key) { return find(key) != nullptr; }

const toml::node* TomlTableReader::node(std::string_view key) { return find(key); }

int TomlTableReader::lineOf(std::string_view key) const {
  const toml::node* node = table_ == nullptr ? nullptr : table_->get(key);
  return node == nullptr ? 0 : static_cast<int>(node->source().begin.line);
}

std::string TomlTableReader::where(std::string_view key) const {
  const toml::node* node = table_ == nullptr ? nullptr : table_->get(key);
  const std::string at = node != nullptr ? sourceLine(source_, *node) : source_;
  return at + ": [" + table_name_ + "] " + std::string(key);
}

void TomlTableReader::fail(std::string_view key, const std::string& what) const {
  throw ConfigError(where(key) + ": " + what);
}

void TomlTableReader::failBetween(std::string_view key_a, std::string_view key_b, const std::string& what) const {
  const int line = std::max(lineOf(key_a), lineOf(key_b));
  const std::string at = line > 0 ? source_ + ":" + std::to_string(line) : source_;
  throw ConfigError(at + ": [" + table_name_ + "] " + what);
}

double TomlTableReader::number(std::string_view key, double fallback, double min, double max, const char* unit) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  const std::optional<double> value = node->value<double>();
  if (!value || !(node->is_floating_point() || node->is_integer()))
    fail(key, std::string("expected a number in ") + unit);
  if (!(*value >= min && *value <= max)) {
    std::ostringstream o;
    o << *value << " is out of range, expected " << min << " .. " << max << " " << unit;
    fail(key, o.str());
  }
  return *value;
}

double TomlTableReader::finite(std::string_view key, double fallback, const char* unit) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  const std::optional<double> value = finiteValue(*node);
  if (!value) fail(key, std::string("expected a finite number in ") + unit);
  return *value;
}

std::int64_t TomlTableReader::integer(std::string_view key, std::int64_t fallback, std::int64_t min, std::int64_t max) {
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

Vec3 TomlTableReader::vec3(std::string_view key, const Vec3& fallback, const char* unit) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  const toml::array* a = node->as_array();
  const std::string expected = std::string("expected an array of 3 numbers in ") + unit;
  if (a == nullptr || a->size() != 3) fail(key, expected);
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    const std::optional<double> e = finiteValue(*a->get(static_cast<std::size_t>(i)));
    if (!e) fail(key, expected);
    v(i) = *e;
  }
  return v;
}

Mat3 TomlTableReader::mat3(std::string_view key, const Mat3& fallback) {
  const toml::node* node = find(key);
  if (node == nullptr) return fallback;
  const toml::array* rows = node->as_array();
  const char* expected = "expected a 3x3 matrix as a list of 3 rows of 3 numbers";
  if (rows == nullptr || rows->size() != 3) fail(key, expected);
  Mat3 m;
  for (int r = 0; r < 3; ++r) {
    const toml::array* row = rows->get(static_cast<std::size_t>(r))->as_array();
    if (row == nullptr || row->size() != 3) fail(key, expected);
    for (int c = 0; c < 3; ++c) {
      const std::optional<double> e = finiteValue(*row->get(static_cast<std::size_t>(c)));
      if (!e) fail(key, expected);
      m(r, c) = *e;
    }
  }
  return m;
}

std::string TomlTableReader::path(std::string_view key, const std::string& fallback, const std::string& base_dir) {
  std::string value = string(key, fallback);
  if (value.empty()) return value;
  if (value.front() != '/' && !base_dir.empty()) value = base_dir + "/" + value;
  return value;
}

void TomlTableReader::rejectUnknownKeys(std::string_view hint) const {
  if (table_ == nullptr) return;
  for (auto&& [key, node] : *table_) {
    if (std::find(known_.begin(), known_.end(), key.str()) == known_.end()) {
      std::string list;
      for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
      if (!hint.empty()) list += "; " + std::string(hint);
      throw ConfigError(sourceLine(source_, node) + ": [" + table_name_ + "] " + std::string(key.str()) +
                        ": unknown key (expected one of: " + list + ")");
    }
  }
}

}  // namespace headingd::core
