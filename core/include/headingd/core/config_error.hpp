#pragma once
#include <stdexcept>

namespace headingd::core {

// Bad configuration: the message names the file, the line, the key and what was expected.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace headingd::core
