#include "headingd/lcm_export/csv_table.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

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

CsvTable::CsvTable(std::filesystem::path final_path) : final_path_(std::move(final_path)) {
  temp_path_ = final_path_;
  temp_path_ += ".tmp";
  file_ = std::fopen(temp_path_.c_str(), "wb");
  if (file_ == nullptr) {
    throw std::runtime_error(temp_path_.string() + ": cannot create: " + std::strerror(errno));
  }
  buffer_.reserve(1 << 16);
}

CsvTable::~CsvTable() {
  if (file_ != nullptr) std::fclose(file_);
  if (!finished_) {
    std::error_code ignored;
    std::filesystem::remove(temp_path_, ignored);
  }
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
  if (!buffer_.empty() && std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) {
    write_failed_ = true;
  }
  buffer_.clear();
}

void CsvTable::finish() {
  flushBuffer();
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (write_failed_ || !closed) {
    throw std::runtime_error(temp_path_.string() + ": write failed: " + std::strerror(errno));
  }
  std::error_code ec;
  std::filesystem::rename(temp_path_, final_path_, ec);
  if (ec) throw std::runtime_error(final_path_.string() + ": cannot rename into place: " + ec.message());
  finished_ = true;
}

}  // namespace headingd::lcm_export
