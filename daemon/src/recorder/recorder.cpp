#include "headingd/daemon/recorder/recorder.hpp"

#include <spdlog/spdlog.h>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "headingd/daemon/recorder/recorder_folder.hpp"
#include "headingd/daemon/recorder/recorder_writer.hpp"

namespace headingd::daemon {

RecorderStream::RecorderStream(std::string name, std::size_t ring_lines) : ring_(std::move(name), ring_lines) {}

bool RecorderStream::write(std::string_view line) noexcept {
  if (!accepting_.load(std::memory_order_acquire)) return false;
  if (line.size() > kMaxLineBytes || (!line.empty() && std::memchr(line.data(), '\n', line.size()) != nullptr)) {
    refused_.store(refused_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    ++lost_since_last_push_;
    return false;
  }
  RecorderLine entry;
  entry.lost_before = lost_since_last_push_;
  entry.length = static_cast<std::uint16_t>(line.size());
  if (!line.empty()) std::memcpy(entry.text, line.data(), line.size());
  if (!ring_.push(entry)) {  // counted by the ring
    ++lost_since_last_push_;
    return false;
  }
  lost_since_last_push_ = 0;
  return true;
}

Recorder::Recorder(RecorderConfig config, std::vector<std::string> stream_names) : config_(std::move(config)) {
  std::vector<RecorderStream*> streams;
  for (std::string& name : stream_names) {
    for (const auto& s : streams_) {
      if (s->name() == name) throw std::invalid_argument("recorder: stream '" + name + "' is named twice");
    }
    // The rings are made only when recording: 256 bytes a line.
    streams_.push_back(std::make_unique<RecorderStream>(std::move(name), config_.enabled ? config_.ring_lines : 1));
    streams.push_back(streams_.back().get());
  }
  writer_ = std::make_unique<RecorderWriter>(config_, std::move(streams));
}

Recorder::~Recorder() { stop(); }

RecorderStream& Recorder::stream(std::string_view name) {
  for (const auto& s : streams_) {
    if (s->name() == name) return *s;
  }
  throw std::invalid_argument("recorder: no stream named '" + std::string(name) + "'");
}

void Recorder::start(const std::vector<std::pair<std::string, std::string>>& files) {
  if (!folder_.empty()) return;
  if (!config_.enabled) {
    spdlog::info("recorder: off: {}", config_.off_reason.empty() ? "[recorder] enabled = false" : config_.off_reason);
    return;
  }
  folder_ = makeRecordingFolder(config_.dir, std::chrono::system_clock::now(), files);
  spdlog::info("recorder: recording to {} (segments up to {} bytes or {} s, at most {} bytes under {})", folder_,
               config_.segment_max_bytes, config_.segment_max_age_s, config_.total_max_bytes, config_.dir);
  writer_->start(folder_);
  for (const auto& s : streams_) s->setAccepting(true);
}

void Recorder::stop() {
  for (const auto& s : streams_) s->setAccepting(false);
  writer_->stop();
}

RecorderCounters Recorder::counters() const {
  const RecorderTally& t = writer_->tally();
  RecorderCounters c;
  c.lines_written = t.lines_written.load(std::memory_order_relaxed);
  c.bytes_written = t.bytes_written.load(std::memory_order_relaxed);
  c.lines_dropped_io = t.lines_dropped_io.load(std::memory_order_relaxed);
  c.write_errors = t.write_errors.load(std::memory_order_relaxed);
  c.segments_opened = t.segments_opened.load(std::memory_order_relaxed);
  c.segments_deleted = t.segments_deleted.load(std::memory_order_relaxed);
  c.bytes_on_disk = t.bytes_on_disk.load(std::memory_order_relaxed);
  for (const auto& s : streams_) {
    c.lines_dropped_ring_full += s->ring().stats().dropped;
    c.lines_refused += s->refused();
  }
  return c;
}

}  // namespace headingd::daemon
