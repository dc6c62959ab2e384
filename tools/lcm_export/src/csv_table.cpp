#include "headingd/lcm_export/csv_table.hpp"

namespace headingd::lcm_export {

void appendCsvCell(std::string& out, std::string_view cell) {
  if (cell.find_first_of(",\"\r\n") == std::string_view::npos) {
    out.append(cell);
    return;
  }
  out.push_back('"');
  for (const char c : cell) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  out.push_back('"');
}

CsvTable::CsvTable(std::filesystem::path final_path) : final_path_(std::move(final_path)), file_(final_path_.string()) {
  buffer_.reserve(1 << 16);
}

void CsvTable::writeRow(const std::vector<std::string>& cells) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) buffer_.push_back(',');
    appendCsvCell(buffer_, cells[i]);
  }
  buffer_.push_back('\n');
  if (buffer_.size() >= (1 << 16)) flushBuffer();
}

void CsvTable::flushBuffer() {
  file_.write(buffer_);
  buffer_.clear();
}

void CsvTable::finish() {
  flushBuffer();
  file_.commit();
}

}  // namespace headingd::lcm_export
