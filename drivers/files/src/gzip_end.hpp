#pragma once
// What zlib says about a gzip stream once gzread() has stopped: a stream whose compressed data
// or CRC-32/length trailer (RFC 1952 §2.2) is missing is a file cut short (a copy interrupted, a
// log ended by a power loss); a failed data, CRC or length check is a corrupt file. zlib hands
// out the bytes it could inflate in both cases, so the reader must ask.
#include <zlib.h>

#include <cstdint>
#include <string>

namespace headingd::files {

// True when the input ended inside a gzip stream (zlib's "unexpected end of file").
inline bool gzipEndMissing(gzFile file) {
  int code = Z_OK;
  gzerror(file, &code);
  return code == Z_BUF_ERROR;
}

// "PATH: truncated gzip file: ..." for a stream whose end is missing.
std::string gzipEndMissingMessage(const std::string& path, std::uint64_t bytes_read);

// "PATH: corrupt gzip file: <zlib's reason>" (or "read error: ..." for an I/O error), for a
// gzread() that returned -1.
std::string gzipReadErrorMessage(gzFile file, const std::string& path);

}  // namespace headingd::files
