#pragma once
// parseCanConfig for a document the caller has already parsed with toml++ (the daemon parses
// its configuration file once and hands each table to its owner).
#include <toml++/toml.h>

#include "headingd/can/can_config.hpp"

namespace headingd::can {

CanConfig parseCanTable(const toml::table& can_table, const std::string& source_name, const std::string& config_dir);

}  // namespace headingd::can
