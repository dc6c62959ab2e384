#include "headingd/files/gzip_file.hpp"

#include <zlib.h>

#include <cerrno>
#include <cstring>

#include "gzip_end.hpp"

namespace headingd::files {

MaybeCutText readMaybeGzipLog(const std::string& path, std::uint64_t limit) {
  InputFile input(path, limit);
  gzFile file = gzdopen(input.fd(), "rb");
  if (file == nullptr) throw FileError(path + ": cannot open: " + std::strerror(errno));
  input.release();  // zlib closes it
  MaybeCutText result;
  std::string& data = result.text;
  char buffer[1 << 16];
  while (true) {
    const int n = gzread(file, buffer, sizeof buffer);
    if (n < 0) {
      const std::string message = gzipReadErrorMessage(file, path);
      gzclose(file);
      throw FileError(message);
    }
    if (n == 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
    if (limit != 0 && data.size() > limit) {  // a gzip stream may inflate far beyond its size on disk
      gzclose(file);
      throw FileError(path + ": holds more than the " + bytesText(limit) + " such a file may have");
    }
  }
  result.end_missing = gzipEndMissing(file);
  gzclose(file);
  return result;
}

std::string readMaybeGzipFile(const std::string& path, std::uint64_t limit) {
  MaybeCutText read = readMaybeGzipLog(path, limit);
  if (read.end_missing) throw FileError(gzipEndMissingMessage(path, read.text.size()));
  return std::move(read.text);
}

}  // namespace headingd::files
