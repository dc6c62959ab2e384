#pragma once
// Whole files that may be gzip (zlib reads plain text too): configuration, calibration, WMM
// coefficients, NMEA and candump logs. Errors are FileError (input_file.hpp), naming the file.
#include <cstdint>
#include <string>

#include "headingd/files/input_file.hpp"  // FileError and the size limits

namespace headingd::files {

// The whole file, decompressed if it is gzip, of at most `limit` bytes decompressed (one of
// input_file.hpp's limits). Throws FileError naming the file when it is not a regular file
// (a FIFO, a device, a directory), larger than the limit, when its gzip stream is corrupt
// (data, CRC or length check) and when the stream ends before its trailer ("truncated gzip
// file"): a cut file is never taken for a whole one.
std::string readMaybeGzipFile(const std::string& path, std::uint64_t limit);

// For a log that a power loss may have cut (the daemon's candump and NMEA log sources): the
// text zlib could read and whether the gzip stream's end was missing, instead of throwing for
// that. Other errors throw as readMaybeGzipFile's.
struct MaybeCutText {
  std::string text;
  bool end_missing = false;
};
MaybeCutText readMaybeGzipLog(const std::string& path, std::uint64_t limit);

}  // namespace headingd::files
