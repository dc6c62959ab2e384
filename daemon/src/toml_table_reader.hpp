#pragma once
// Reads the keys of one TOML table with defaults, type and range checks, and at the end
// rejects the keys nobody asked for. Every error is a core::ConfigError that names
// file:line, [table] key and what was expected (the style of core/params_toml.cpp).
#include <cstdint>
#include <initializer_list>
#include <set>
#include <string>
#include <string_view>
#include <toml++/toml.h>
#include <vector>

#include "headingd/core/params_toml.hpp"

namespace headingd::daemon {

class TomlTableReader {
 public:
  // `table` may be null (table absent: every key keeps its default).
  TomlTableReader(const toml::table* table, std::string source, std::string table_name);

  double number(std::string_view key, double fallback, double min, double max, const char* unit);
  std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t min, std::int64_t max);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, const std::string& fallback);
  // One of `choices`.
  std::string choice(std::string_view key, const std::string& fallback, std::initializer_list<const char*> choices);
  std::vector<std::int64_t> integerArray(std::string_view key, std::int64_t min, std::int64_t max);
  // A path: relative paths are taken from `base_dir`; "" stays "". With must_exist, a path
  // that cannot be opened for reading is an error.
  std::string path(std::string_view key, const std::string& fallback, const std::string& base_dir, bool must_exist);

  // "file:line: [table] key" of a key present in the table (for messages of later checks).
  std::string where(std::string_view key) const;
  [[noreturn]] void fail(std::string_view key, const std::string& what) const;
  // Throws for the first key of the table that was never asked for.
  void rejectUnknownKeys() const;

 private:
  const toml::node* find(std::string_view key);

  const toml::table* table_;
  std::string source_;
  std::string table_name_;
  std::set<std::string, std::less<>> known_;
};

// "file:line" of a node.
std::string sourceLine(const std::string& source, const toml::node& node);

}  // namespace headingd::daemon
