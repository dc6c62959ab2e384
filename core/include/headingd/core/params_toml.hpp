#pragma once
// EstimatorParams from the [estimator] table of a TOML document. Parsing only: the caller
// reads the file, so core stays free of I/O.
#include <toml++/toml.h>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/config_error.hpp"
#include "headingd/core/estimator_params.hpp"

namespace headingd::core {

class TomlTableReader;

// Description of one tunable, used for parsing, range checks and documentation tests.
struct ParamSpec {
  const char* key;
  double EstimatorParams::*member;
  double min;  // inclusive
  double max;  // inclusive
  const char* unit;
};
const std::vector<ParamSpec>& estimatorParamSpecs();

// The [estimator] table of a document already parsed (null: absent, every key its default).
// Unknown keys, wrong types, out-of-range values and inconsistent pairs throw ConfigError
// naming `source_name`, the line and the key.
EstimatorParams parseEstimatorTable(const toml::table* estimator, const std::string& source_name);

// The same from a document that holds only an [estimator] table (config/estimator.toml,
// headingd-replay --config).
EstimatorParams parseEstimatorParams(std::string_view toml_text, const std::string& source_name);

// Checks between parameters (hysteresis order, level order, the restore's age against the
// background headings' period); throws ConfigError at the line of the key in `table`'s file.
void validateEstimatorParams(const EstimatorParams& p, const TomlTableReader& table);
// The same for parameters that come from no file (the message names `source_name`).
void validateEstimatorParams(const EstimatorParams& p, const std::string& source_name);

}  // namespace headingd::core
