#pragma once
// The black box: producer threads (the sources, the estimator loop) hand text lines to the
// recorder, each through a lock-free ring of its own; one writer thread at normal scheduling
// drains the rings and writes each stream to rotated files `<stream>.<NNNNNN>.log` in a
// recording folder, under a total cap. A slow, stuck or full disk never delays a producer:
// its ring fills, lines are dropped and counted, and the file says where with a note line
// `# lost <N> lines` (lines starting with '#' are notes in every stream).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/recorder/recorder_config.hpp"

namespace headingd::daemon {

// For STATUS, published as counters "recorder_<name>" (appendRecorderCounters).
struct RecorderCounters {
  std::uint64_t lines_written = 0, bytes_written = 0;
  std::uint64_t lines_dropped_ring_full = 0;  // producer found the ring full (slow or stuck disk)
  std::uint64_t lines_refused = 0;            // longer than RecorderStream::kMaxLineBytes or with a '\n'
  std::uint64_t lines_dropped_io = 0;         // written to no file because of a write/open error (full disk, I/O error)
  std::uint64_t write_errors = 0;             // failed open/write/fsync calls (and failed deletions by the cap)
  std::uint64_t segments_opened = 0, segments_deleted = 0;  // deleted = by the total cap
  std::uint64_t bytes_on_disk = 0;                          // under dir, as the cap sees it
};

// Each counter with its STATUS name, in a fixed order.
template <class F>
void forEachRecorderCounter(const RecorderCounters& c, F&& f) {
  f("recorder_lines_written", c.lines_written);
  f("recorder_bytes_written", c.bytes_written);
  f("recorder_lines_dropped_ring_full", c.lines_dropped_ring_full);
  f("recorder_lines_refused", c.lines_refused);
  f("recorder_lines_dropped_io", c.lines_dropped_io);
  f("recorder_write_errors", c.write_errors);
  f("recorder_segments_opened", c.segments_opened);
  f("recorder_segments_deleted", c.segments_deleted);
  f("recorder_bytes_on_disk", c.bytes_on_disk);
}

inline constexpr std::size_t kRecorderMaxLineBytes = 240;

// One ring slot: a line and how many lines its producer lost just before it, so the loss
// note lands exactly where the lines are missing. 256 bytes.
struct RecorderLine {
  std::uint64_t lost_before = 0;
  std::uint16_t length = 0;
  char text[kRecorderMaxLineBytes];
};

class RecorderStream {  // one producer thread per stream
 public:
  // A longer line is refused (returns false, counted as dropped): producers split their data.
  static constexpr std::size_t kMaxLineBytes = kRecorderMaxLineBytes;

  RecorderStream(std::string name, std::size_t ring_lines);
  RecorderStream(const RecorderStream&) = delete;
  RecorderStream& operator=(const RecorderStream&) = delete;

  // Producer thread only. Never blocks, never allocates: copies `line` (no '\n'; the writer
  // adds it) into the ring. false = dropped and counted (ring full, too long, or holding a
  // '\n'), or recording is off (before start(), after stop(), or disabled: not counted).
  bool write(std::string_view line) noexcept;

  const std::string& name() const { return ring_.name(); }

  // The writer's side.
  SampleRing<RecorderLine>& ring() { return ring_; }
  std::uint64_t refused() const { return refused_.load(std::memory_order_relaxed); }
  void setAccepting(bool accepting) { accepting_.store(accepting, std::memory_order_release); }

 private:
  SampleRing<RecorderLine> ring_;
  std::atomic<bool> accepting_{false};
  std::atomic<std::uint64_t> refused_{0};
  std::uint64_t lost_since_last_push_ = 0;  // producer thread only
};

class RecorderWriter;

class Recorder {
 public:
  Recorder(RecorderConfig config, std::vector<std::string> stream_names);  // e.g. {"can", "gps", "estimator"}
  ~Recorder();                                                             // stop()
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  // Valid for the Recorder's life; throws std::invalid_argument for an unknown name.
  RecorderStream& stream(std::string_view name);

  // Creates <dir>/<UTC start time as YYYY-MM-DDTHH-MM-SSZ>/ (suffix -2, -3 ... if it exists),
  // writes each of `files` (name in the folder, content) there, then starts the writer
  // thread. Throws std::runtime_error with a clear message if the folder or a file cannot be
  // made (nothing is recorded then). With recording off (config.enabled false) it logs
  // config.off_reason once at info and starts nothing.
  void start(const std::vector<std::pair<std::string, std::string>>& files);
  // Writes what the rings still hold, closes the files, joins the thread. Idempotent.
  void stop();
  const std::string& folder() const { return folder_; }  // "" before start() or when off
  RecorderCounters counters() const;                     // any thread

 private:
  RecorderConfig config_;
  std::vector<std::unique_ptr<RecorderStream>> streams_;
  std::string folder_;
  std::unique_ptr<RecorderWriter> writer_;
};

}  // namespace headingd::daemon
