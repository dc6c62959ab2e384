#include "headingd/files/csv_row_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>

#include "headingd/files/decimal_number.hpp"
#include "headingd/files/numeric_csv.hpp"

namespace headingd::files {
namespace {

bool isBlank(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && (isBlank(s.back()) || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

bool parseDouble(std::string_view text, double* out) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);  // from_chars rejects '+'
  if (text.empty()) return false;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), *out);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

}  // namespace

CsvRowReader::CsvRowReader(const std::string& path, const std::vector<std::string>& required,
                           const std::vector<std::string>& optional)
    : lines_(path) {
  std::string_view line;
  if (!lines_.next(&line)) throw CsvError(path + ": empty file, expected a header line");
  for (auto field : splitFields(line)) header_.emplace_back(trim(field));
  // A column named twice leaves it unclear which one holds the data: refused, not the first taken.
  auto find = [&](const std::string& name) {
    const auto first = std::find(header_.begin(), header_.end(), name);
    if (first != header_.end()) {
      if (const auto second = std::find(first + 1, header_.end(), name); second != header_.end()) {
        throw CsvError(path + ":1: column '" + name + "' is named twice in the header (fields " +
                       std::to_string(first - header_.begin() + 1) + " and " +
                       std::to_string(second - header_.begin() + 1) + "): which one holds the data is not clear");
      }
    }
    return static_cast<std::size_t>(first - header_.begin());
  };
  for (const auto& name : required) {
    const std::size_t index = find(name);
    if (index == header_.size()) {
      const auto like = headerNameLike(name);
      throw CsvError(
          path + ":1: header has no column '" + name + "'" +
          (like ? " (it has '" + *like + "': names are case-sensitive)" : " (header line required, e.g. t,gyr_x,...)"));
    }
    column_names_.push_back(name);
    field_of_slot_.push_back(index);
  }
  for (const auto& name : optional) {
    const std::size_t index = find(name);
    if (index == header_.size()) continue;
    column_names_.push_back(name);
    field_of_slot_.push_back(index);
  }
  std::size_t needed_fields = 0;
  for (const std::size_t index : field_of_slot_) needed_fields = std::max(needed_fields, index + 1);
  slot_of_field_.assign(needed_fields, -1);
  for (std::size_t slot = 0; slot < field_of_slot_.size(); ++slot) {
    int& slot_of_field = slot_of_field_[field_of_slot_[slot]];
    if (slot_of_field >= 0) fast_path_ = false;  // a column asked for twice: one field, two slots
    slot_of_field = static_cast<int>(slot);
  }
}

std::optional<std::string> CsvRowReader::headerNameLike(const std::string& name) const {
  const auto same_ignoring_case = [&](const std::string& field) {
    return field.size() == name.size() && std::equal(field.begin(), field.end(), name.begin(), [](char a, char b) {
             return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
           });
  };
  for (const auto& field : header_) {
    if (field != name && same_ignoring_case(field)) return field;
  }
  return std::nullopt;
}

std::optional<std::size_t> CsvRowReader::slot(const std::string& name) const {
  const auto it = std::find(column_names_.begin(), column_names_.end(), name);
  if (it == column_names_.end()) return std::nullopt;
  return static_cast<std::size_t>(it - column_names_.begin());
}

bool CsvRowReader::next(std::span<double> values) {
  std::string_view line;
  while (lines_.next(&line)) {
    if (trim(line).empty()) continue;  // a trailing blank line is not a row
    if (!fast_path_ || !parseFast(line, values)) parseExact(line, values);
    ++rows_;
    return true;
  }
  return false;
}

// The common case in one pass: fields of plain numbers, walked left to right, each read
// where it lies. Anything unusual (too few fields, a value that does not read) returns false
// and parseExact decides, so both paths accept exactly the same rows.
bool CsvRowReader::parseFast(std::string_view line, std::span<double> values) const {
  const char* p = line.data();
  const char* const end = p + line.size();
  for (std::size_t field = 0; field < slot_of_field_.size(); ++field) {
    if (field > 0) {  // step past the previous field's comma
      const char* comma = static_cast<const char*>(std::memchr(p, ',', static_cast<std::size_t>(end - p)));
      if (comma == nullptr) return false;
      p = comma + 1;
    }
    const int slot = slot_of_field_[field];
    if (slot < 0) continue;
    while (p != end && isBlank(*p)) ++p;
    if (p != end && *p == '+') ++p;
    const auto [ptr, ec] = readDecimal(p, end, &values[static_cast<std::size_t>(slot)]);
    if (ec != std::errc() || ptr == p) return false;
    p = ptr;
    while (p != end && (isBlank(*p) || *p == '\r')) ++p;
    if (p != end && *p != ',') return false;
  }
  return true;
}

// Field by field as readNumericCsv always did: the first problem, in the order the columns
// were asked for, is the error.
void CsvRowReader::parseExact(std::string_view line, std::span<double> values) const {
  const std::string line_number = std::to_string(lines_.lineNumber());
  const auto fields = splitFields(line);
  const std::size_t needed_fields = slot_of_field_.size();
  if (fields.size() < needed_fields) {
    throw CsvError(path() + ":" + line_number + ": " + std::to_string(fields.size()) + " fields, but column '" +
                   header_[needed_fields - 1] + "' is field " + std::to_string(needed_fields));
  }
  for (std::size_t slot = 0; slot < field_of_slot_.size(); ++slot) {
    const std::size_t index = field_of_slot_[slot];
    if (!parseDouble(fields[index], &values[slot])) {
      throw CsvError(path() + ":" + line_number + ": column '" + header_[index] + "' (field " +
                     std::to_string(index + 1) + "): cannot read '" + std::string(trim(fields[index])) +
                     "' as a number");
    }
  }
}

}  // namespace headingd::files
