#include "headingd/core/toml_document.hpp"

namespace headingd::core {
namespace {

// The key written on line `line` (1-based) of `text`, or "" if that line has no `key =`.
std::string keyOnLine(std::string_view text, std::size_t line) {
  for (std::size_t i = 1; i < line && !text.empty(); ++i) {
    const std::size_t nl = text.find('\n');
    text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
  }
  text = text.substr(0, text.find('\n'));
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos) return "";
  std::string_view key = text.substr(0, equals);
  while (!key.empty() && (key.front() == ' ' || key.front() == '\t')) key.remove_prefix(1);
  while (!key.empty() && (key.back() == ' ' || key.back() == '\t')) key.remove_suffix(1);
  return std::string(key);
}

}  // namespace

toml::table parseTomlDocument(std::string_view text, const std::string& source) {
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::string message =
        source + ":" + std::to_string(e.source().begin.line) + ": TOML syntax error: " + std::string(e.description());
    const std::string key = keyOnLine(text, e.source().begin.line);
    if (!key.empty()) message += " (in the value of '" + key + "')";
    throw ConfigError(message);
  }
}

}  // namespace headingd::core
