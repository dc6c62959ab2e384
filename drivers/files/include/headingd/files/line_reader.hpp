#pragma once
// Reads a text file (plain or gzip: zlib reads both) one line at a time through a fixed
// buffer, so memory stays flat whatever the file's length. A line is handed out as a view
// into the buffer, valid until the next call; no copy, no allocation per line.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "headingd/files/input_file.hpp"  // kMaxLineBytes

namespace headingd::files {

class LineReader {
 public:
  // Throws CsvError "PATH: cannot open: REASON", or naming why PATH is no regular file (a FIFO,
  // a device, a directory: input_file.hpp). A line longer than `max_line_bytes` (rounded up to
  // the buffer's 256 kiB) throws CsvError "PATH:LINE: a line longer than ..." from next().
  explicit LineReader(std::string path, std::size_t max_line_bytes = kMaxLineBytes);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line without its '\n' (a '\r' before it stays); a last line without '\n' is a
  // line too. False at the end of the file. Throws CsvError naming the file when zlib cannot
  // read on: "PATH: corrupt gzip file: ..." (data, CRC or length check failed), "PATH:
  // truncated gzip file: ..." (the stream ends before its trailer), "PATH: read error: ...".
  bool next(std::string_view* line);
  // 1-based number of the line last handed out (0 before the first).
  std::size_t lineNumber() const { return line_number_; }
  const std::string& path() const { return path_; }

 private:
  bool refill();  // false when the file has no more bytes

  std::string path_;
  std::size_t max_line_bytes_;
  void* file_ = nullptr;            // gzFile (kept out of this header so users need not include zlib)
  std::unique_ptr<char[]> buffer_;  // not zeroed: every byte used is read first
  std::size_t capacity_ = 0;
  std::size_t begin_ = 0;  // first byte not handed out yet
  std::size_t end_ = 0;    // one past the last byte read
  bool at_eof_ = false;
  std::size_t line_number_ = 0;
  std::uint64_t bytes_read_ = 0;  // of text (decompressed), for the truncation message
};

}  // namespace headingd::files
