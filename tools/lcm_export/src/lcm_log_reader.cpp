#include "headingd/lcm_export/lcm_log_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "headingd/files/input_file.hpp"

namespace headingd::lcm_export {
namespace {

std::uint64_t bigEndian(const std::uint8_t* bytes, int count) {
  std::uint64_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

}  // namespace

LcmLogReader::LcmLogReader(const std::filesystem::path& path) : path_(path.string()) {
  // A regular file only, opened without blocking (files/input_file.hpp); read an event at a
  // time, each of bounded size, so the log's length does not matter.
  files::InputFile input(path_);
  file_ = ::fdopen(input.fd(), "rb");
  if (file_ == nullptr) throw std::runtime_error(path_ + ": cannot open: " + std::strerror(errno));
  input.release();  // the FILE closes it
  // Big sequential reads: the log is read twice, front to back.
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  std::error_code ec;
  file_size_ = std::filesystem::file_size(path, ec);
  if (ec) file_size_ = 0;
}

LcmLogReader::~LcmLogReader() {
  if (file_ != nullptr) std::fclose(file_);
}

bool LcmLogReader::readExactly(void* out, std::size_t bytes) {
  const std::size_t got = std::fread(out, 1, bytes, file_);
  offset_ += got;
  if (got == bytes) return true;
  if (std::ferror(file_)) throw std::runtime_error(path_ + ": read error at byte " + std::to_string(offset_));
  return false;
}

bool LcmLogReader::next(LcmLogEvent& event) {
  const std::uint64_t start = offset_;
  std::uint8_t header[kLcmLogEventHeaderBytes];
  const std::size_t got = std::fread(header, 1, sizeof header, file_);
  offset_ += got;
  if (got == 0 && std::feof(file_)) return false;
  if (got != sizeof header) {
    if (std::ferror(file_)) throw std::runtime_error(path_ + ": read error at byte " + std::to_string(offset_));
    throw LcmLogError(start,
                      "truncated event: the file ends " + std::to_string(got) + " bytes into the 28-byte event header");
  }
  const auto sync = static_cast<std::uint32_t>(bigEndian(header, 4));
  if (sync != kLcmLogSyncWord) {
    char text[64];
    std::snprintf(text, sizeof text, "bad sync word 0x%08X (expected 0x%08X)", static_cast<unsigned>(sync),
                  static_cast<unsigned>(kLcmLogSyncWord));
    throw LcmLogError(start, text);
  }
  event.offset = start;
  event.event_number = static_cast<std::int64_t>(bigEndian(header + 4, 8));
  event.utime = static_cast<std::int64_t>(bigEndian(header + 12, 8));
  const auto channel_bytes = static_cast<std::int32_t>(bigEndian(header + 20, 4));
  const auto data_bytes = static_cast<std::int32_t>(bigEndian(header + 24, 4));
  if (channel_bytes < 1 || channel_bytes > kMaxChannelBytes) {
    throw LcmLogError(start, "absurd channel length " + std::to_string(channel_bytes) + " (expected 1.." +
                                 std::to_string(kMaxChannelBytes) + ")");
  }
  if (data_bytes < 0 || data_bytes > kMaxDataBytes) {
    throw LcmLogError(start, "absurd data length " + std::to_string(data_bytes) + " (expected 0.." +
                                 std::to_string(kMaxDataBytes) + ")");
  }
  const std::uint64_t body = static_cast<std::uint64_t>(channel_bytes) + static_cast<std::uint64_t>(data_bytes);
  // Checked against what the file holds before anything is allocated: a corrupt length within
  // the bounds above would otherwise cost up to 256 MiB (and bad_alloc under a memory limit).
  if (file_size_ > 0 && body > file_size_ - std::min(offset_, file_size_)) {
    throw LcmLogError(start, "truncated event: it needs " + std::to_string(kLcmLogEventHeaderBytes + body) +
                                 " bytes, the file ends after " + std::to_string(file_size_ - start));
  }
  event.channel.resize(static_cast<std::size_t>(channel_bytes));
  event.data.resize(static_cast<std::size_t>(data_bytes));
  if (!readExactly(event.channel.data(), event.channel.size()) || !readExactly(event.data.data(), event.data.size())) {
    throw LcmLogError(start, "truncated event: it needs " + std::to_string(kLcmLogEventHeaderBytes + body) +
                                 " bytes, the file ends after " + std::to_string(offset_ - start));
  }
  return true;
}

}  // namespace headingd::lcm_export
