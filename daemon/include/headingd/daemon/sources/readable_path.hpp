#pragma once
// A path key of a configuration table, for the daemon's tables and the file sources'.
#include <cstdint>
#include <string>
#include <string_view>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/files/input_file.hpp"  // the size limits

namespace headingd::daemon {

// The path `key` names (relative to `base_dir`). When `required`, it must open at start-up as
// a regular file (not a FIFO, device or directory: files/input_file.hpp) of at most `limit`
// bytes on disk (0 = no limit, for logs read a line at a time); the reader's fail() names the
// key otherwise.
std::string readablePath(core::TomlTableReader& r, std::string_view key, const std::string& fallback,
                         const std::string& base_dir, bool required, std::uint64_t limit);

}  // namespace headingd::daemon
