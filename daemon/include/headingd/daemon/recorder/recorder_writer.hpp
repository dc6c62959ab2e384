#pragma once
// The recorder's thread: every period it drains each stream's ring into that stream's
// segments, syncs and rotates them, and keeps the directory under its cap. Normal
// scheduling, whatever the thread that starts it runs at: it may block in the disk, the
// estimator must not.
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "headingd/daemon/recorder/recorder.hpp"
#include "headingd/daemon/recorder/recorder_disk_cap.hpp"
#include "headingd/daemon/recorder/recorder_segments.hpp"
#include "headingd/daemon/recorder/recorder_tally.hpp"

namespace headingd::daemon {

class RecorderWriter {
 public:
  static constexpr std::chrono::milliseconds kPeriod{20};

  RecorderWriter(const RecorderConfig& config, std::vector<RecorderStream*> streams);
  ~RecorderWriter();

  // Starts the thread writing into `folder` (made by makeRecordingFolder).
  void start(const std::string& folder);
  // Drains what the rings hold, closes the files, joins. Idempotent.
  void stop();

  const RecorderTally& tally() const { return tally_; }

 private:
  struct StreamState {
    RecorderStream* stream = nullptr;
    std::unique_ptr<RecorderSegmentWriter> file;
    std::uint64_t lost_announced = 0;  // lines lost that the ring's lines announced
    bool said_ring_full = false;
    bool said_refused = false;
  };

  void run();
  void drain(StreamState& s, RecorderSegmentWriter::Clock::time_point now);
  void sayFirstLosses(StreamState& s);

  const RecorderConfig& config_;
  RecorderTally tally_;
  std::vector<StreamState> streams_;
  std::unique_ptr<RecorderDiskCap> cap_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_requested_ = false;
};

}  // namespace headingd::daemon
