#pragma once
// One CSV file (RFC 4180 quoting: comma-separated, lines end in "\n", a cell quoted when it
// holds a comma, a double quote, CR or LF, its quotes doubled), written through
// files::OutputFile (a temporary file renamed into place by finish()): an interrupted run
// never leaves a half-written file under the final name.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/files/output_file.hpp"

namespace headingd::lcm_export {

// Appends `cell` to `out`, quoted when it must be.
void appendCsvCell(std::string& out, std::string_view cell);

class CsvTable {
 public:
  // Creates the temporary file; throws files::FileError when it cannot.
  explicit CsvTable(std::filesystem::path final_path);
  ~CsvTable() = default;  // the temporary file is removed unless finish() succeeded
  CsvTable(const CsvTable&) = delete;
  CsvTable& operator=(const CsvTable&) = delete;

  void writeRow(const std::vector<std::string>& cells);
  // Flushes, closes and renames the file into place; throws files::FileError on a write
  // error (the temporary file is then removed).
  void finish();
  const std::filesystem::path& path() const { return final_path_; }

 private:
  void flushBuffer();
  std::filesystem::path final_path_;
  files::OutputFile file_;
  std::string buffer_;
};

}  // namespace headingd::lcm_export
