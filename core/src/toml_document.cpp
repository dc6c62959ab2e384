#include "headingd/core/toml_document.hpp"

namespace headingd::core {

toml::table parseTomlDocument(std::string_view text, const std::string& source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw ConfigError(source + ":" + std::to_string(e.source().begin.line) + ": TOML syntax error: " +
                      std::string(e.description()));
  }
}

}  // namespace headingd::core
