#pragma once
// A path key of a configuration table, for the daemon's tables and the file sources'.
#include <string>
#include <string_view>

#include "headingd/core/toml_table_reader.hpp"

namespace headingd::daemon {

// The path `key` names (relative to `base_dir`), which must be readable at start-up when
// `required` (the reader's fail() names the key otherwise).
std::string readablePath(core::TomlTableReader& r, std::string_view key, const std::string& fallback,
                         const std::string& base_dir, bool required);

}  // namespace headingd::daemon
