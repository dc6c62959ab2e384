#pragma once
// A TOML document from text, the one way every configuration and calibration file is parsed:
// a syntax error becomes a ConfigError "source:line: TOML syntax error: what", followed by
// the key when the broken line is a `key = value` line.
#include <toml++/toml.h>
#include <string>
#include <string_view>

#include "headingd/core/config_error.hpp"

namespace headingd::core {

toml::table parseTomlDocument(std::string_view text, const std::string& source);

}  // namespace headingd::core
