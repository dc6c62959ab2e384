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

// The whole file, decompressed if it is gzip, of at most `limit` bytes decompressed (one of
// input_file.hpp's limits). Throws CsvError naming the file when it is not a regular file
// (a FIFO, a device, a directory), larger than the limit, when its gzip stream is corrupt
// (data, CRC or length check) and when the stream ends before its trailer ("truncated gzip
// file"): a cut file is never taken for a whole one.
std::string readMaybeGzipFile(const std::string& path, std::uint64_t limit);

// For a log that a power loss may have cut (the daemon's candump and NMEA log sources): the
// text zlib could read and whether the gzip stream's end was missing, instead of throwing for
// that. Other errors throw as readMaybeGzipFile's.
struct MaybeCutText {
  std::string text;
  bool end_missing = false;
};
MaybeCutText readMaybeGzipLog(const std::string& path, std::uint64_t limit);

}  // namespace headingd::files
