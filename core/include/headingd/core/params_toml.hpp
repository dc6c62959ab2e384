#pragma once
// EstimatorParams from the [estimator] table of a TOML document. Parsing only: the caller
// reads the file, so core stays free of I/O.
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/estimator_params.hpp"

namespace headingd::core {

// Bad configuration: the message names the file, the line, the key and what was expected.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Description of one tunable, used for parsing, range checks and documentation tests.
struct ParamSpec {
  const char* key;
  double EstimatorParams::*member;
  double min;  // inclusive
  double max;  // inclusive
  const char* unit;
};
const std::vector<ParamSpec>& estimatorParamSpecs();

// Parses `toml_text` (named `source_name` in messages). Keys absent from the document keep
// their defaults; unknown keys, wrong types and out-of-range values throw ConfigError.
EstimatorParams parseEstimatorParams(std::string_view toml_text, const std::string& source_name);

// Cross-checks between parameters (hysteresis order, level order); throws ConfigError.
// `key_lines` (key → line in the source), when given, lets the message name the line of the
// offending key.
void validateEstimatorParams(const EstimatorParams& p, const std::string& source_name,
                             const std::map<std::string, int>* key_lines = nullptr);

}  // namespace headingd::core
