#pragma once
// One CSV file (RFC 4180 quoting: comma-separated, lines end in "\n", a cell quoted when it
// holds a comma, a double quote, CR or LF, its quotes doubled), written under a temporary
// name and renamed into place by finish(): an interrupted run never leaves a half-written
// file under the final name.
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace headingd::lcm_export {

// Appends `cell` to `out`, quoted when it must be.
void appendCsvCell(std::string& out, std::string_view cell);

class CsvTable {
 public:
  // Creates `<final_path>.tmp`; throws std::runtime_error when it cannot.
  explicit CsvTable(std::filesystem::path final_path);
  ~CsvTable();  // removes the temporary file unless finish() succeeded
  CsvTable(const CsvTable&) = delete;
  CsvTable& operator=(const CsvTable&) = delete;

  void writeRow(const std::vector<std::string>& cells);
  // Flushes, closes and renames the file into place; throws std::runtime_error on a write
  // error (the temporary file is then removed).
  void finish();
  const std::filesystem::path& path() const { return final_path_; }

 private:
  void flushBuffer();
  std::filesystem::path final_path_;
  std::filesystem::path temp_path_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
  bool write_failed_ = false;
  bool finished_ = false;
};

}  // namespace headingd::lcm_export
