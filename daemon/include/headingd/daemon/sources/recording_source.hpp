#pragma once
// A black-box recording (drivers/recording, daemon/README.md "Black box") as a source: the
// IMU samples and GPS epochs the live estimator got, decoded again from the recorded CAN
// frames and serial bytes, played on the log clock (playback_clock.hpp) at [playback] speed.
// Each GPS epoch carries the number of IMU samples it went in after live
// (GpsRingEntry::after_imu_samples), so the estimator takes it at the same place whatever the
// speed and the ticks: with the recording's configuration (its replay.toml), HEADING and
// ATTITUDE are the live run's, bit for bit.
//
// A file has no deadline: when a ring is full the source waits for room instead of dropping.
#include <atomic>
#include <boost/asio/steady_timer.hpp>
#include <memory>
#include <optional>
#include <string>

#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/sources/asio_source.hpp"
#include "headingd/daemon/sources/playback_clock.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/recording/recording_reader.hpp"
#include "headingd/recording/recording_setup.hpp"

namespace headingd::daemon {

// [recording]: dir = the recording folder.
struct RecordingSourceConfig : SourceConfig {
  std::string dir;
  std::unique_ptr<Source> createSource(SourceContext& context) const override;
};
std::unique_ptr<SourceConfig> parseRecordingSource(const SourceTable& table);

class RecordingSource final : public AsioSource<recording::RecordingCounters> {
 public:
  // Reads the folder's header and configuration (throws core::ConfigError).
  RecordingSource(std::string name, const std::string& dir, AtEnd at_end, const PlaybackClock* clock,
                  std::uint16_t source_index, SampleRing<ImuRingEntry>* imu_ring, SampleRing<GpsRingEntry>* gps_ring);
  ~RecordingSource() override;

  const char* kind() const override { return "recording"; }
  bool readsAtRealTimePace() const override { return clock_->speed <= 1.0; }
  void report(SourceReport& out) const override;
  bool wantsExit() const override { return finished_.load() && at_end_ == AtEnd::kExit; }
  bool playing() const override { return !finished_.load(); }
  std::optional<std::int64_t> firstLogNs() { return reader_->firstTimeNs(); }

 private:
  void onStart() override { playDue(); }
  recording::RecordingCounters currentCounters() const override { return reader_->counters(); }
  void playDue();  // io thread: every step due by now, then the timer for the next
  bool pushStep(const recording::RecordingStep& step, std::int64_t now_ns);  // false: ring full
  void waitUntil(std::int64_t mono_ns);
  void finish(const std::string& error);

  AtEnd at_end_;
  const PlaybackClock* clock_;
  SampleRing<ImuRingEntry>* imu_ring_;
  SampleRing<GpsRingEntry>* gps_ring_;
  recording::RecordingSetup setup_;
  std::unique_ptr<recording::RecordingReader> reader_;
  std::optional<recording::RecordingStep> pending_;
  std::uint64_t imu_pushed_ = 0;
  boost::asio::steady_timer timer_;
  std::atomic<bool> finished_{false};
  mutable std::mutex error_mutex_;
  std::string error_;
};

}  // namespace headingd::daemon
