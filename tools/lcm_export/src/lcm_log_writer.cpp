#include "headingd/lcm_export/lcm_log_writer.hpp"

#include <stdexcept>

#include "headingd/lcm_export/lcm_log_reader.hpp"

namespace headingd::lcm_export {
namespace {

template <class T>
void putBigEndian(std::uint8_t* out, T value) {
  const auto v = static_cast<std::uint64_t>(value);
  for (std::size_t i = 0; i < sizeof(T); ++i) out[i] = static_cast<std::uint8_t>(v >> (8 * (sizeof(T) - 1 - i)));
}

}  // namespace

LcmLogWriter::LcmLogWriter(const std::string& path) : path_(path) { file_ = std::make_unique<files::OutputFile>(path); }

LcmLogWriter::~LcmLogWriter() = default;

void LcmLogWriter::write(std::string_view channel, std::int64_t utime_us, const std::uint8_t* data, std::size_t size) {
  std::uint8_t header[kLcmLogEventHeaderBytes];
  putBigEndian(header, kLcmLogSyncWord);
  putBigEndian(header + 4, next_event_++);
  putBigEndian(header + 12, utime_us);
  putBigEndian(header + 20, static_cast<std::int32_t>(channel.size()));
  putBigEndian(header + 24, static_cast<std::int32_t>(size));
  if (file_ == nullptr) throw std::runtime_error(path_ + ": written after close");
  std::FILE* f = file_->stream();
  if (std::fwrite(header, 1, sizeof header, f) != sizeof header ||
      std::fwrite(channel.data(), 1, channel.size(), f) != channel.size() || std::fwrite(data, 1, size, f) != size) {
    throw std::runtime_error(path_ + ": write failed");
  }
}

void LcmLogWriter::close() {
  if (file_ == nullptr) return;
  file_->commit();
  file_.reset();
}

}  // namespace headingd::lcm_export
