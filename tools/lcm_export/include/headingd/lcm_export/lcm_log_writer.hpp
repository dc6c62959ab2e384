#pragma once
// Writes an LCM log file in the format lcm-logger writes and LcmLogReader reads
// (lcm_log_reader.hpp has the layout), without LCM's library: a tool that only writes logs
// does not load liblcm and GLib at start-up. Written through files::OutputFile: the log
// appears under its name only when close() succeeded.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/files/output_file.hpp"

namespace headingd::lcm_export {

class LcmLogWriter {
 public:
  // Throws files::FileError when the file cannot be created.
  explicit LcmLogWriter(const std::string& path);
  ~LcmLogWriter();
  LcmLogWriter(const LcmLogWriter&) = delete;
  LcmLogWriter& operator=(const LcmLogWriter&) = delete;

  // One event, numbered in order from 0. Throws std::runtime_error on a write error.
  void write(std::string_view channel, std::int64_t utime_us, const std::uint8_t* data, std::size_t size);
  // An lcm-gen message, encoded.
  template <class Message>
  void write(std::string_view channel, std::int64_t utime_us, const Message& m) {
    buffer_.resize(static_cast<std::size_t>(m.getEncodedSize()));
    m.encode(buffer_.data(), 0, static_cast<int>(buffer_.size()));
    write(channel, utime_us, buffer_.data(), buffer_.size());
  }
  // Flushes, closes and renames into place; throws files::FileError if that fails. Idempotent.
  // Without it (an error stopped the run) nothing appears under the name.
  void close();

 private:
  std::unique_ptr<files::OutputFile> file_;
  std::string path_;
  std::int64_t next_event_ = 0;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace headingd::lcm_export
