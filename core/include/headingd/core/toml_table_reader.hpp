#pragma once
// The one way a table of a TOML file is read: typed getters with defaults and range checks,
// and at the end a check that rejects the keys nobody asked for. Every error is a ConfigError
// that names "file:line: [table] key: what was expected". Used for the daemon's tables, the
// estimator's parameters, the calibration file and the drivers' [can] and [gps] tables; each
// owner reads its own table from the toml::table it was handed, parsed once.
// No I/O: whether a path names a readable file is for the caller (fail() says where).
#include <toml++/toml.h>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/config_error.hpp"
#include "headingd/core/quaternion.hpp"  // Vec3, Mat3

namespace headingd::core {

class TomlTableReader {
 public:
  // `table` may be null (table absent: every key keeps its default).
  TomlTableReader(const toml::table* table, std::string source, std::string table_name);

  // Whether the table sets `key` (which counts as asked for).
  bool has(std::string_view key);
  // The key's node for a form of its own (null if absent), e.g. a signal reference.
  const toml::node* node(std::string_view key);

  double number(std::string_view key, double fallback, double min, double max, const char* unit);
  // Any finite number.
  double finite(std::string_view key, double fallback, const char* unit);
  std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t min, std::int64_t max);
  bool boolean(std::string_view key, bool fallback);
  std::string string(std::string_view key, const std::string& fallback);
  // One of `choices`.
  std::string choice(std::string_view key, const std::string& fallback, std::initializer_list<const char*> choices);
  std::vector<std::int64_t> integerArray(std::string_view key, std::int64_t min, std::int64_t max);
  // [x, y, z] of finite numbers; a 3x3 matrix as a list of 3 rows of 3 finite numbers.
  Vec3 vec3(std::string_view key, const Vec3& fallback, const char* unit);
  Mat3 mat3(std::string_view key, const Mat3& fallback);
  // A path: relative paths are taken from `base_dir`; "" stays "".
  std::string path(std::string_view key, const std::string& fallback, const std::string& base_dir);

  // "file:line: [table] key" ("file: [table] key" if the table does not set it).
  std::string where(std::string_view key) const;
  // The line that sets `key`, 0 if none.
  int lineOf(std::string_view key) const;
  [[noreturn]] void fail(std::string_view key, const std::string& what) const;
  // For a check between two keys: "file:line: [table] what", at the line of whichever of
  // them the file sets (the later one); `what` names both.
  [[noreturn]] void failBetween(std::string_view key_a, std::string_view key_b, const std::string& what) const;
  // Throws for the first key of the table that was never asked for; `hint` ends the message
  // (e.g. "config/gps.toml documents them").
  void rejectUnknownKeys(std::string_view hint = {}) const;

  const std::string& source() const { return source_; }

 private:
  const toml::node* find(std::string_view key);

  const toml::table* table_;
  std::string source_;
  std::string table_name_;
  std::vector<std::string> known_;  // in the order asked, for the unknown-key message
};

// "file:line" of a node.
std::string sourceLine(const std::string& source, const toml::node& node);

// The table `name` of `doc`, null if absent; a key of that name that is not a table throws.
const toml::table* tableOf(const toml::table& doc, std::string_view name, const std::string& source);

// Throws for a top-level key of `doc` that is not one of `names` or is not a table.
void rejectUnknownTables(const toml::table& doc, const std::string& source, std::initializer_list<const char*> names);
void rejectUnknownTables(const toml::table& doc, const std::string& source, const std::vector<std::string>& names);

}  // namespace headingd::core
