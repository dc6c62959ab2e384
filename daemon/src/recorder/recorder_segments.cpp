#include "headingd/daemon/recorder/recorder_segments.hpp"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "headingd/daemon/recorder/recorder_folder.hpp"
#include "headingd/daemon/recorder/write_fully.hpp"

namespace headingd::daemon {
namespace {

std::uint64_t newlines(const char* first, const char* last) {
  return static_cast<std::uint64_t>(std::count(first, last, '\n'));
}

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

RecorderSegmentWriter::RecorderSegmentWriter(std::string folder, std::string stream, const RecorderConfig& config,
                                             RecorderTally& tally, RecorderDiskCap& cap)
    : folder_(std::move(folder)),
      stream_(std::move(stream)),
      segment_max_bytes_(config.segment_max_bytes),
      segment_max_age_(
          std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(config.segment_max_age_s))),
      tally_(tally),
      cap_(cap) {
  buffer_.reserve(kBufferBytes);
}

RecorderSegmentWriter::~RecorderSegmentWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void RecorderSegmentWriter::line(std::string_view text, std::uint64_t lost_before, Clock::time_point now) {
  lost_unannounced_ += lost_before;
  const std::size_t bytes = text.size() + 1 + (lost_unannounced_ > 0 ? 32 : 0);  // a note is shorter than 32
  if (fd_ >= 0 && segment_bytes_ > 0 && segment_bytes_ + bytes > segment_max_bytes_) rotate(now);
  if (fd_ >= 0 && buffer_.size() + bytes > kBufferBytes) writeOut(now, false);
  if (!segmentReady(now)) {
    ++lost_unannounced_;
    RecorderTally::add(tally_.lines_dropped_io, 1);
    return;
  }
  if (lost_unannounced_ > 0) appendNote();
  buffer_.append(text);
  buffer_.push_back('\n');
  segment_bytes_ += text.size() + 1;
}

void RecorderSegmentWriter::tick(Clock::time_point now) {
  if (fd_ >= 0 && now - opened_at_ >= segment_max_age_) {
    rotate(now);
  } else if (fd_ >= 0 && now - last_sync_ >= kSyncPeriod) {
    writeOut(now, true);
  }
}

void RecorderSegmentWriter::finish(std::uint64_t lost, Clock::time_point now) {
  lost_unannounced_ += lost;
  if (lost_unannounced_ > 0 && segmentReady(now, true)) appendNote();
  writeOut(now, true);
  closeSegment();
}

bool RecorderSegmentWriter::segmentReady(Clock::time_point now, bool ignore_backoff) {
  if (fd_ >= 0) return true;
  if (failing_ && now < retry_at_ && !ignore_backoff) return false;
  path_ = folder_ + "/" + segmentFileName(stream_, number_);
  // Blocks only if the disk does; the producers are not waiting for this thread.
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    failed("open", errno, now);  // the same number is tried again: no file was made
    return false;
  }
  RecorderTally::add(tally_.segments_opened, 1);
  opened_at_ = now;
  last_sync_ = now;
  segment_bytes_ = 0;
  segment_written_ = 0;
  unsynced_ = false;
  return true;
}

void RecorderSegmentWriter::appendNote() {
  char note[48];
  const int n =
      std::snprintf(note, sizeof note, "# lost %llu lines\n", static_cast<unsigned long long>(lost_unannounced_));
  buffer_.append(note, static_cast<std::size_t>(n));
  notes_in_buffer_.emplace_back(buffer_.size(), lost_unannounced_);
  segment_bytes_ += static_cast<std::size_t>(n);
  lost_unannounced_ = 0;
}

void RecorderSegmentWriter::writeOut(Clock::time_point now, bool sync) {
  if (fd_ < 0) return;
  const WriteOutcome w = writeFully(fd_, buffer_.data(), buffer_.size());
  // Lines count as written when their '\n' reached the file; the notes are not lines.
  std::uint64_t notes_written = 0, lost_in_notes_not_written = 0;
  for (const auto& [end, lost] : notes_in_buffer_) {
    if (end <= w.written) {
      ++notes_written;
    } else {
      ++lost_in_notes_not_written;  // counted below as a line; corrected here
      lost_unannounced_ += lost;
    }
  }
  const char* data = buffer_.data();
  RecorderTally::add(tally_.lines_written, newlines(data, data + w.written) - notes_written);
  RecorderTally::add(tally_.bytes_written, w.written);
  cap_.grew(w.written);
  segment_written_ += w.written;
  if (w.written > 0) unsynced_ = true;
  if (w.error != 0) {
    const std::uint64_t dropped = newlines(data + w.written, data + buffer_.size()) - lost_in_notes_not_written;
    RecorderTally::add(tally_.lines_dropped_io, dropped);
    lost_unannounced_ += dropped;
  }
  buffer_.clear();
  notes_in_buffer_.clear();
  if (w.error != 0) {
    failed("write", w.error, now);
    return;
  }
  if (failing_ && w.written > 0) {
    failing_ = false;
    backoff_ = kFirstBackoff;
    spdlog::info("recorder: writing {} again", path_);
  }
  if (sync && unsynced_) {
    last_sync_ = now;
    // EINVAL: the file cannot be synced (a pipe or device), there is nothing to wait for.
    if (::fdatasync(fd_) != 0 && errno != EINVAL) {
      failed("sync", errno, now);  // what is written may be lost, how much is not known
      return;
    }
    unsynced_ = false;
  }
}

void RecorderSegmentWriter::closeSegment() {
  if (fd_ < 0) return;
  ::close(fd_);  // after fdatasync, or after an error already counted
  fd_ = -1;
  cap_.segmentClosed(path_, segment_written_);
  ++number_;
  segment_bytes_ = 0;
  segment_written_ = 0;
}

void RecorderSegmentWriter::rotate(Clock::time_point now) {
  writeOut(now, true);
  closeSegment();
}

void RecorderSegmentWriter::failed(const char* what, int error, Clock::time_point now) {
  RecorderTally::add(tally_.write_errors, 1);
  buffer_.clear();
  notes_in_buffer_.clear();
  closeSegment();
  if (!failing_) {
    spdlog::warn(
        "recorder: cannot {} {}: {}; lines of stream '{}' are dropped (counted on STATUS) until a new "
        "segment can be written, next try in {:.0f} s",
        what, path_, std::strerror(error), stream_, seconds(backoff_));
  }
  failing_ = true;
  retry_at_ = now + backoff_;
  backoff_ = std::min(backoff_ * 2, kLongestBackoff);
}

}  // namespace headingd::daemon
