#pragma once
// Numeric columns, by header name, of a CSV file (plain or gzip), one row at a time: the
// streaming form of readNumericCsv, with the same rules and error messages. Each row is
// parsed in place in the reader's buffer with std::from_chars; nothing is allocated per row,
// so memory stays flat whatever the file's length.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/files/line_reader.hpp"

namespace headingd::files {

class CsvRowReader {
 public:
  // Opens the file and reads its header line. `required`: missing from the header →
  // CsvError naming file, line 1 and the column. `optional`: read when present.
  CsvRowReader(const std::string& path, const std::vector<std::string>& required,
               const std::vector<std::string>& optional = {});

  // The columns read, in the order asked for (required first, then the optional ones the
  // header has); a row's values come in this order.
  const std::vector<std::string>& columns() const { return column_names_; }
  // Where column `name` is in a row's values, if it is read.
  std::optional<std::size_t> slot(const std::string& name) const;
  const std::vector<std::string>& header() const { return header_; }
  // A header field that is `name` in another case ("mag_Z" for "mag_z"), for error messages.
  std::optional<std::string> headerNameLike(const std::string& name) const;

  // Reads the next data row into `values` (columns().size() of them). False at the end of
  // the file. Blank lines are skipped. Throws CsvError naming file, line and column for a
  // row with too few fields or a field that is not a number (any form std::from_chars
  // reads, with surrounding blanks and a leading '+' allowed; empty is an error).
  bool next(std::span<double> values);
  // Data rows handed out so far.
  std::size_t rows() const { return rows_; }
  std::size_t lineNumber() const { return lines_.lineNumber(); }
  const std::string& path() const { return lines_.path(); }

 private:
  bool parseFast(std::string_view line, std::span<double> values) const;
  void parseExact(std::string_view line, std::span<double> values) const;

  LineReader lines_;
  std::vector<std::string> header_;
  std::vector<std::string> column_names_;
  std::vector<std::size_t> field_of_slot_;  // file field index of each slot
  std::vector<int> slot_of_field_;          // slot of each field up to the last one read, -1 if unread
  bool fast_path_ = true;
  std::size_t rows_ = 0;
};

}  // namespace headingd::files
