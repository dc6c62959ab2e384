#pragma once
// Reads numeric columns, by header name, from a CSV file that is plain text or gzip
// (zlib reads both). The first line must be the header. Columns not asked for are ignored
// and never parsed. Errors name the file, the 1-based line and the column.
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "headingd/files/input_file.hpp"  // the size limits

namespace headingd::files {

class CsvError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct NumericCsv {
  std::string path;
  std::vector<std::string> header;
  // Requested columns that the header has, each with one value per data row.
  std::map<std::string, std::vector<double>> columns;
  std::size_t rows = 0;

  bool has(const std::string& name) const { return columns.count(name) != 0; }
  const std::vector<double>& column(const std::string& name) const { return columns.at(name); }
};

// `required`: missing from the header → CsvError. `optional`: read when present.
// Fields may hold any number std::from_chars reads, including nan and inf; an empty or
// unparsable field, or a row with fewer fields than the header, is an error.
NumericCsv readNumericCsv(const std::string& path, const std::vector<std::string>& required,
                          const std::vector<std::string>& optional = {});

}  // namespace headingd::files
