#pragma once
// A TOML document from text, the one way every configuration and calibration file is read:
// a syntax error becomes a ConfigError "source:line: TOML syntax error: what".
#include <string>
#include <string_view>
#include <toml++/toml.h>

#include "headingd/core/params_toml.hpp"

namespace headingd::core {

toml::table parseTomlDocument(std::string_view text, const std::string& source);

}  // namespace headingd::core
