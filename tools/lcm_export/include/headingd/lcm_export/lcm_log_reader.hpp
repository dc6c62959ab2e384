#pragma once
// Reads an LCM log file (as lcm-logger writes it) event by event, streaming, and says at
// which byte a bad or truncated log goes wrong. The format (LCM's eventlog): each event is
//   uint32 sync word 0xEDA1DA01, int64 event number, int64 timestamp [us],
//   int32 channel length, int32 data length, the channel's bytes, the data bytes,
// every integer big-endian. lcm::LogFile would skip to the next sync word silently; this
// reader stops at the first bad event so that the exporter can name it.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace headingd::lcm_export {

inline constexpr std::uint32_t kLcmLogSyncWord = 0xEDA1DA01u;
inline constexpr std::uint64_t kLcmLogEventHeaderBytes = 4 + 8 + 8 + 4 + 4;
// LCM's channel names have at most 63 bytes; a length outside 1..1024 is not a channel.
inline constexpr std::int32_t kMaxChannelBytes = 1024;
// LCM's UDP transport carries messages of up to a few hundred kB; a length beyond 256 MiB is
// corruption, not a message (and would be allocated before it could be checked otherwise).
inline constexpr std::int32_t kMaxDataBytes = 256 * 1024 * 1024;

struct LcmLogEvent {
  std::uint64_t offset = 0;  // of the sync word in the file
  std::int64_t event_number = 0;
  std::int64_t utime = 0;  // lcm-logger: receive time, microseconds since 1970
  std::string channel;
  std::vector<std::uint8_t> data;  // the encoded message, fingerprint first
};

// A log that is not a valid LCM log from `offset` on (the start of the bad event).
class LcmLogError : public std::runtime_error {
 public:
  LcmLogError(std::uint64_t offset, const std::string& what) : std::runtime_error(what), offset_(offset) {}
  std::uint64_t offset() const { return offset_; }

 private:
  std::uint64_t offset_;
};

class LcmLogReader {
 public:
  // Throws std::runtime_error when the file cannot be opened.
  explicit LcmLogReader(const std::filesystem::path& path);
  ~LcmLogReader();
  LcmLogReader(const LcmLogReader&) = delete;
  LcmLogReader& operator=(const LcmLogReader&) = delete;

  // The next event into `event` (its buffers are reused); false at the end of the file after
  // a whole event. Throws LcmLogError for a bad sync word, an absurd length or an event cut
  // off by the end of the file, std::runtime_error for a read error.
  bool next(LcmLogEvent& event);
  // Bytes consumed so far: the offset of the next event.
  std::uint64_t offset() const { return offset_; }
  std::uint64_t fileSize() const { return file_size_; }

 private:
  bool readExactly(void* out, std::size_t bytes);  // false at EOF before `bytes`
  std::FILE* file_ = nullptr;
  std::string path_;
  std::uint64_t offset_ = 0;
  std::uint64_t file_size_ = 0;
};

}  // namespace headingd::lcm_export
