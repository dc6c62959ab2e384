#include "headingd/daemon/recorder/recorder_writer.hpp"

#include <pthread.h>
#include <sched.h>
#include <spdlog/spdlog.h>

namespace headingd::daemon {

RecorderWriter::RecorderWriter(const RecorderConfig& config, std::vector<RecorderStream*> streams) : config_(config) {
  for (RecorderStream* s : streams) streams_.push_back({s, nullptr});
}

RecorderWriter::~RecorderWriter() { stop(); }

void RecorderWriter::start(const std::string& folder) {
  if (thread_.joinable()) return;
  cap_ = std::make_unique<RecorderDiskCap>(config_.dir, folder, config_.total_max_bytes, tally_);
  for (StreamState& s : streams_) {
    s.file = std::make_unique<RecorderSegmentWriter>(folder, s.stream->name(), config_, tally_, *cap_);
  }
  {
    std::lock_guard lock(mutex_);
    stop_requested_ = false;
  }
  thread_ = std::thread([this] { run(); });
}

void RecorderWriter::stop() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_requested_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void RecorderWriter::run() {
  // A thread inherits its creator's policy: the recorder must never run at real-time priority.
  sched_param normal{};
  normal.sched_priority = 0;
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
  pthread_setname_np(pthread_self(), "recorder");

  cap_->scan();
  cap_->enforce();
  for (;;) {
    bool stopping = false;
    {
      std::unique_lock lock(mutex_);
      stopping = wake_.wait_for(lock, kPeriod, [this] { return stop_requested_; });
    }
    const auto now = RecorderSegmentWriter::Clock::now();
    for (StreamState& s : streams_) {
      drain(s, now);
      sayFirstLosses(s);
      if (!stopping) s.file->tick(now);
    }
    if (stopping) break;
    cap_->enforce();
  }
  // The rings were drained after the stop request: what producers lost at the very end has
  // no later line to announce it.
  const auto now = RecorderSegmentWriter::Clock::now();
  for (StreamState& s : streams_) {
    const RingStats ring = s.stream->ring().stats();
    const std::uint64_t lost = ring.dropped + s.stream->refused();
    s.file->finish(lost > s.lost_announced ? lost - s.lost_announced : 0, now);
    s.lost_announced = lost;
  }
  cap_->enforce();
}

void RecorderWriter::drain(StreamState& s, RecorderSegmentWriter::Clock::time_point now) {
  s.stream->ring().drain([&](const RecorderLine& line) {
    s.lost_announced += line.lost_before;
    s.file->line(std::string_view(line.text, line.length), line.lost_before, now);
  });
}

// Producers must not log (they are real-time threads): their first loss is said here, once.
void RecorderWriter::sayFirstLosses(StreamState& s) {
  if (!s.said_ring_full && s.stream->ring().stats().dropped > 0) {
    s.said_ring_full = true;
    spdlog::warn(
        "recorder: stream '{}' dropped lines: its ring of {} lines was full (the disk is slow or stuck); "
        "counted on STATUS as recorder_lines_dropped_ring_full, not logged again",
        s.stream->name(), s.stream->ring().capacity());
  }
  if (!s.said_refused && s.stream->refused() > 0) {
    s.said_refused = true;
    spdlog::warn(
        "recorder: stream '{}' was given a line longer than {} bytes or holding a newline; such lines are "
        "refused and counted on STATUS as recorder_lines_refused, not logged again",
        s.stream->name(), RecorderStream::kMaxLineBytes);
  }
}

}  // namespace headingd::daemon
