#include "gzip_end.hpp"

namespace headingd::files {

std::string gzipEndMissingMessage(const std::string& path, std::uint64_t bytes_read) {
  return path + ": truncated gzip file: the compressed data ends after " + std::to_string(bytes_read) +
         " bytes of text, before the end of the gzip stream (its CRC and length)";
}

std::string gzipReadErrorMessage(gzFile file, const std::string& path) {
  int code = Z_OK;
  std::string reason = gzerror(file, &code);
  // zlib puts the path it was given in front of its message: ours (gzopen), or "<fd:N>" for a
  // file opened first and handed over (gzdopen). Ours is already there.
  if (reason.starts_with(path + ": ")) {
    reason.erase(0, path.size() + 2);
  } else if (reason.starts_with("<fd:")) {
    const std::size_t end = reason.find(">: ");
    if (end != std::string::npos) reason.erase(0, end + 3);
  }
  if (code == Z_DATA_ERROR) return path + ": corrupt gzip file: " + reason;
  return path + ": read error: " + reason;
}

}  // namespace headingd::files
