#pragma once
// One stream's files in a recording folder: `<stream>.<NNNNNN>.log`, one line per line, in
// large blocks (a 64 KiB buffer written out when full and, with fdatasync, at least once a
// second, so a power loss costs about a second). A segment is closed and the next opened
// when it would grow beyond segment_max_bytes or is older than segment_max_age_s; segments
// are opened when the first line for them comes. Lost lines (a full ring, a failed write)
// are announced by a note line `# lost <N> lines` before the next line that is written.
// A failed open, write or sync drops lines (counted), is logged once at warn, and a new
// segment is tried after a back-off of 5 s doubling to 60 s; the first write that works
// again is logged at info. Writer thread only.
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "headingd/daemon/recorder/recorder_config.hpp"
#include "headingd/daemon/recorder/recorder_disk_cap.hpp"
#include "headingd/daemon/recorder/recorder_tally.hpp"

namespace headingd::daemon {

class RecorderSegmentWriter {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::size_t kBufferBytes = 64 * 1024;
  static constexpr Clock::duration kSyncPeriod = std::chrono::seconds(1);
  static constexpr Clock::duration kFirstBackoff = std::chrono::seconds(5);
  static constexpr Clock::duration kLongestBackoff = std::chrono::seconds(60);

  RecorderSegmentWriter(std::string folder, std::string stream, const RecorderConfig& config, RecorderTally& tally,
                        RecorderDiskCap& cap);
  ~RecorderSegmentWriter();
  RecorderSegmentWriter(const RecorderSegmentWriter&) = delete;
  RecorderSegmentWriter& operator=(const RecorderSegmentWriter&) = delete;

  // One line (without '\n'); `lost_before` lines were lost just before it.
  void line(std::string_view text, std::uint64_t lost_before, Clock::time_point now);
  // Writes out and syncs once a sync period has passed; rotates a segment that is too old.
  void tick(Clock::time_point now);
  // At the end: `lost` more lines that no later line announces get their note (one more
  // try to open a segment for it, back-off or not); then writes out, syncs and closes.
  void finish(std::uint64_t lost, Clock::time_point now);

 private:
  bool segmentReady(Clock::time_point now, bool ignore_backoff = false);
  void appendNote();
  void writeOut(Clock::time_point now, bool sync);
  void closeSegment();
  void rotate(Clock::time_point now);
  void failed(const char* what, int error, Clock::time_point now);

  std::string folder_;
  std::string stream_;
  std::uint64_t segment_max_bytes_;
  Clock::duration segment_max_age_;
  RecorderTally& tally_;
  RecorderDiskCap& cap_;

  std::string buffer_;
  std::vector<std::pair<std::size_t, std::uint64_t>> notes_in_buffer_;  // (end offset, lines it announces)
  int fd_ = -1;
  std::uint64_t number_ = 1;  // of the segment open, or of the next one
  std::string path_;
  std::uint64_t segment_bytes_ = 0;    // written and buffered
  std::uint64_t segment_written_ = 0;  // reached the file
  bool unsynced_ = false;
  Clock::time_point opened_at_{};
  Clock::time_point last_sync_{};
  std::uint64_t lost_unannounced_ = 0;
  bool failing_ = false;  // since a failure, until a write works again
  Clock::time_point retry_at_{};
  Clock::duration backoff_ = kFirstBackoff;
};

}  // namespace headingd::daemon
