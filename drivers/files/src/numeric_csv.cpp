#include "headingd/files/numeric_csv.hpp"

#include <zlib.h>

#include <cerrno>
#include <cstring>

#include "headingd/files/csv_row_reader.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::files {

std::string readMaybeGzipFile(const std::string& path, std::uint64_t limit) {
  gzFile file = nullptr;
  try {
    InputFile input(path, limit);
    file = gzdopen(input.fd(), "rb");
    if (file == nullptr) throw CsvError(path + ": cannot open: " + std::strerror(errno));
    input.release();  // zlib closes it
  } catch (const FileError& e) {
    throw CsvError(e.what());
  }
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
    if (limit != 0 && data.size() > limit) {  // a gzip stream may inflate far beyond its size on disk
      gzclose(file);
      throw CsvError(path + ": holds more than the " + bytesText(limit) + " such a file may have");
    }
  }
  gzclose(file);
  return data;
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
