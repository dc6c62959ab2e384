#include "headingd/files/numeric_csv.hpp"

#include <zlib.h>

#include <cerrno>
#include <cstring>

#include "gzip_end.hpp"
#include "headingd/files/csv_row_reader.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::files {

MaybeCutText readMaybeGzipLog(const std::string& path, std::uint64_t limit) {
  gzFile file = nullptr;
  try {
    InputFile input(path, limit);
    file = gzdopen(input.fd(), "rb");
    if (file == nullptr) throw CsvError(path + ": cannot open: " + std::strerror(errno));
    input.release();  // zlib closes it
  } catch (const FileError& e) {
    throw CsvError(e.what());
  }
  MaybeCutText result;
  std::string& data = result.text;
  char buffer[1 << 16];
  while (true) {
    const int n = gzread(file, buffer, sizeof buffer);
    if (n < 0) {
      const std::string message = gzipReadErrorMessage(file, path);
      gzclose(file);
      throw CsvError(message);
    }
    if (n == 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
    if (limit != 0 && data.size() > limit) {  // a gzip stream may inflate far beyond its size on disk
      gzclose(file);
      throw CsvError(path + ": holds more than the " + bytesText(limit) + " such a file may have");
    }
  }
  result.end_missing = gzipEndMissing(file);
  gzclose(file);
  return result;
}

std::string readMaybeGzipFile(const std::string& path, std::uint64_t limit) {
  MaybeCutText read = readMaybeGzipLog(path, limit);
  if (read.end_missing) throw CsvError(gzipEndMissingMessage(path, read.text.size()));
  return std::move(read.text);
}

NumericCsv readNumericCsv(const std::string& path, const std::vector<std::string>& required,
                          const std::vector<std::string>& optional) {
  CsvRowReader reader(path, required, optional);
  NumericCsv csv;
  csv.path = path;
  csv.header = reader.header();
  std::vector<std::vector<double>*> destinations;
  for (const auto& name : reader.columns()) destinations.push_back(&csv.columns[name]);
  std::vector<double> row(reader.columns().size());
  while (reader.next(row)) {
    for (std::size_t i = 0; i < row.size(); ++i) destinations[i]->push_back(row[i]);
  }
  csv.rows = reader.rows();
  return csv;
}

}  // namespace headingd::files
