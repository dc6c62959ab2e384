#include "headingd/files/numeric_csv.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <string_view>

namespace headingd::files {
namespace {

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

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool parseDouble(std::string_view text, double* out) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);  // from_chars rejects '+'
  if (text.empty()) return false;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), *out);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

}  // namespace

std::string readMaybeGzipFile(const std::string& path) {
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr) throw CsvError(path + ": cannot open: " + std::strerror(errno));
  std::string data;
  char buffer[1 << 16];
  while (true) {
    const int n = gzread(file, buffer, sizeof buffer);
    if (n < 0) {
      int code = 0;
      const std::string message = gzerror(file, &code);
      gzclose(file);
      throw CsvError(path + ": read error: " + message);
    }
    if (n == 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
  }
  gzclose(file);
  return data;
}

NumericCsv readNumericCsv(const std::string& path, const std::vector<std::string>& required,
                          const std::vector<std::string>& optional) {
  const std::string text = readMaybeGzipFile(path);
  NumericCsv csv;
  csv.path = path;

  std::string_view rest(text);
  std::size_t line_number = 0;
  auto next_line = [&](std::string_view* line) {
    if (rest.empty()) return false;
    const std::size_t nl = rest.find('\n');
    *line = rest.substr(0, nl);
    rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
    ++line_number;
    return true;
  };

  std::string_view line;
  if (!next_line(&line)) throw CsvError(path + ": empty file, expected a header line");
  for (auto field : splitFields(line)) csv.header.emplace_back(trim(field));

  // (column index in the file, destination) for each requested column present.
  std::vector<std::pair<std::size_t, std::vector<double>*>> wanted;
  auto find = [&](const std::string& name) {
    return std::find(csv.header.begin(), csv.header.end(), name) - csv.header.begin();
  };
  for (const auto& name : required) {
    const auto index = static_cast<std::size_t>(find(name));
    if (index == csv.header.size()) {
      throw CsvError(path + ":1: header has no column '" + name + "' (header line required, e.g. t,gyr_x,...)");
    }
    wanted.emplace_back(index, &csv.columns[name]);
  }
  for (const auto& name : optional) {
    const auto index = static_cast<std::size_t>(find(name));
    if (index != csv.header.size()) wanted.emplace_back(index, &csv.columns[name]);
  }
  std::size_t needed_fields = 0;
  for (const auto& [index, _] : wanted) needed_fields = std::max(needed_fields, index + 1);

  while (next_line(&line)) {
    if (trim(line).empty()) continue;  // a trailing blank line is not a row
    const auto fields = splitFields(line);
    if (fields.size() < needed_fields) {
      throw CsvError(path + ":" + std::to_string(line_number) + ": " + std::to_string(fields.size()) +
                     " fields, but column '" + csv.header[needed_fields - 1] + "' is field " +
                     std::to_string(needed_fields));
    }
    for (const auto& [index, destination] : wanted) {
      double value = 0.0;
      if (!parseDouble(fields[index], &value)) {
        throw CsvError(path + ":" + std::to_string(line_number) + ": column '" + csv.header[index] + "' (field " +
                       std::to_string(index + 1) + "): cannot read '" + std::string(trim(fields[index])) +
                       "' as a number");
      }
      destination->push_back(value);
    }
    ++csv.rows;
  }
  return csv;
}

}  // namespace headingd::files
