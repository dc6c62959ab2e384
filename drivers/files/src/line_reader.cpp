#include "headingd/files/line_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <memory>

#include "gzip_end.hpp"
#include "headingd/files/input_file.hpp"
#include "headingd/files/numeric_csv.hpp"

namespace headingd::files {
namespace {

// Reads of 64 KiB: zlib copies a plain file straight into our buffer when a read is at least
// its own buffer's size (so that is half of ours). Larger buffers read no faster: each of
// their pages costs a page fault when first touched (about 10 us on a virtual machine, the
// time of ~25 CSV rows), and 256 KiB buffers made a replay 3-9 % slower.
constexpr std::size_t kBufferBytes = 1 << 16;
constexpr unsigned kZlibBufferBytes = 1 << 15;

}  // namespace

LineReader::LineReader(std::string path, std::size_t max_line_bytes)
    : path_(std::move(path)),
      max_line_bytes_(std::max(max_line_bytes, kBufferBytes)),
      buffer_(std::make_unique_for_overwrite<char[]>(kBufferBytes)),
      capacity_(kBufferBytes) {
  gzFile file = nullptr;
  try {
    InputFile input(path_);  // no total limit: read a buffer at a time
    file = gzdopen(input.fd(), "rb");
    if (file == nullptr) throw CsvError(path_ + ": cannot open: " + std::strerror(errno));
    input.release();  // zlib closes it
  } catch (const FileError& e) {
    throw CsvError(e.what());
  }
  gzbuffer(file, kZlibBufferBytes);
  file_ = file;
}

LineReader::~LineReader() { gzclose(static_cast<gzFile>(file_)); }

bool LineReader::refill() {
  if (at_eof_) return false;
  if (begin_ > 0) {  // keep the unfinished line, at the front
    std::memmove(buffer_.get(), buffer_.get() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ == capacity_) {  // a line longer than the buffer
    if (capacity_ >= max_line_bytes_) {
      throw CsvError(path_ + ":" + std::to_string(line_number_ + 1) + ": a line longer than " +
                     bytesText(max_line_bytes_) + " (no line break): not a text file of this kind");
    }
    auto larger = std::make_unique_for_overwrite<char[]>(capacity_ * 2);
    std::memcpy(larger.get(), buffer_.get(), end_);
    buffer_ = std::move(larger);
    capacity_ *= 2;
  }
  const std::size_t room = std::min<std::size_t>(capacity_ - end_, INT_MAX);
  const int n = gzread(static_cast<gzFile>(file_), buffer_.get() + end_, static_cast<unsigned>(room));
  if (n < 0) throw CsvError(gzipReadErrorMessage(static_cast<gzFile>(file_), path_));
  if (n == 0) {
    // A cut gzip stream is an error, not an end: the rows read so far are not the whole file.
    if (gzipEndMissing(static_cast<gzFile>(file_))) {
      throw CsvError(gzipEndMissingMessage(path_, bytes_read_) + ", after line " + std::to_string(line_number_));
    }
    at_eof_ = true;
    return false;
  }
  end_ += static_cast<std::size_t>(n);
  bytes_read_ += static_cast<std::uint64_t>(n);
  return true;
}

bool LineReader::next(std::string_view* line) {
  std::size_t searched = begin_;  // bytes before this hold no '\n'
  while (true) {
    const void* nl = std::memchr(buffer_.get() + searched, '\n', end_ - searched);
    if (nl != nullptr) {
      const std::size_t at = static_cast<std::size_t>(static_cast<const char*>(nl) - buffer_.get());
      *line = std::string_view(buffer_.get() + begin_, at - begin_);
      begin_ = at + 1;
      ++line_number_;
      return true;
    }
    const std::size_t searched_bytes = end_ - begin_;
    if (!refill()) break;
    searched = begin_ + searched_bytes;
  }
  if (begin_ == end_) return false;
  *line = std::string_view(buffer_.get() + begin_, end_ - begin_);  // the last line has no '\n'
  begin_ = end_;
  ++line_number_;
  return true;
}

}  // namespace headingd::files
