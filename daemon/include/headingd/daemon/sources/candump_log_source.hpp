#pragma once
// A `candump -l` log as the IMU source: drivers/can's CandumpReader reads the frames (plain or
// gzip), the same DBC codec and epoch assembler as the live CAN source turn them into
// samples, which go into the IMU ring at the pace of the log's own timestamps
// (playback_clock.hpp), on an Asio steady_timer of the source's own thread.
//
// Sensor time: a sample's t_ns is the log's timestamp of its epoch's first frame (the
// recorder's CLOCK_REALTIME, as a live source's kernel timestamp before the daemon maps it to
// the monotonic clock), so the estimator sees the recorded timing at any speed. Arrival time:
// the monotonic time that frame was due. The open epoch is flushed on the log's time axis
// (before each frame, at that frame's time; can/epoch_flush.hpp), so the samples do not
// depend on how late the timer fired.
//
// Bad times (log_frame_times.hpp): frames far off the times around them are skipped, steps of
// the log's clock are played without waiting; both counted. A gzip log cut short is played
// as far as it goes (log_end_missing on STATUS).
//
// [playback] at_end = "loop": at its end the log plays again from its first frame, every
// frame's time moved on by the clock's loop length (playback_clock.hpp), so the samples'
// times keep increasing; loops_played on STATUS.
#include <atomic>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "headingd/can/can_config.hpp"
#include "headingd/can/can_frame.hpp"
#include "headingd/can/candump_log.hpp"
#include "headingd/can/dbc.hpp"
#include "headingd/can/epoch_assembler.hpp"
#include "headingd/can/imu_frame_codec.hpp"
#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/sources/asio_source.hpp"
#include "headingd/daemon/sources/can_assembler_report.hpp"
#include "headingd/daemon/sources/playback_clock.hpp"
#include "headingd/daemon/sources/source_registry.hpp"

namespace headingd::daemon {

// [candump_log]: a `candump -l` log (plain or gzip) decoded like the live [can] source.
struct CandumpLogSourceConfig : SourceConfig {
  std::string path;             // the log
  std::string can_config_path;  // a TOML file with a [can] table (DBC, signal mapping, counters, epoch window)
  can::CanConfig can;           // read from can_config_path when enabled
  std::unique_ptr<Source> createSource(SourceContext& context) const override;
};
std::unique_ptr<SourceConfig> parseCandumpLogSource(const SourceTable& table);

class CandumpLogSource final : public AsioSource<can::AssemblerCounters> {
 public:
  // Reads the DBC file and the whole log (throws core::ConfigError for the DBC and mapping,
  // files::FileError when the log cannot be read or its gzip stream is corrupt). Lines that are
  // not frames, frames with outlying times and a cut gzip end are counted and logged.
  CandumpLogSource(std::string name, const CandumpLogSourceConfig& config, AtEnd at_end, const PlaybackClock* clock,
                   std::uint16_t source_index, SampleRing<ImuRingEntry>* imu_ring);
  ~CandumpLogSource() override;

  const char* kind() const override { return "candump_log"; }
  bool readsAtRealTimePace() const override { return clock_->speed <= 1.0; }
  void report(SourceReport& out) const override;
  bool wantsExit() const override { return finished_.load() && at_end_ == AtEnd::kExit; }
  bool playing() const override { return !finished_.load(); }

  // Timestamp of the log's first frame played (its own clock), nullopt for a log without frames.
  std::optional<std::int64_t> firstLogNs() const;
  std::optional<std::int64_t> lastLogNs() const;
  // The usual step between two frames of the log's first CAN ID (median of the first
  // thousand): the IMU's sample period. nullopt for a log with fewer than two such frames.
  std::optional<std::int64_t> sampleStepNs() const { return sample_step_ns_; }
  std::size_t frameCount() const { return frames_.size(); }
  const can::CandumpCounters& readerCounters() const { return reader_counters_; }

 private:
  void onStart() override;  // the timer for the first frame; the thread ends when the log is played
  can::AssemblerCounters currentCounters() const override { return assembler_->counters(); }
  void playDue();  // on the io thread: every frame due by now, then the timer for the next
  void pushSamples(const can::AssembledSamples& samples);
  void finish();
  // At the end of the frames: true when the log plays again (at_end = "loop").
  bool startNextLoop();
  // Drops the outliers of `all` into frames_ and their playback times into play_ns_.
  void placeFrames(const std::string& path, const std::vector<can::CanFrame>& all,
                   const std::vector<std::uint64_t>& lines);

  AtEnd at_end_;
  const PlaybackClock* clock_;
  SampleRing<ImuRingEntry>* ring_;
  can::CanConfig can_config_;
  can::DbcDatabase dbc_;
  std::unique_ptr<can::ImuFrameCodec> codec_;
  std::unique_ptr<can::EpochAssembler> assembler_;
  FullScaleWarning full_scale_warning_;
  std::int64_t flush_age_ns_ = 0;
  std::vector<can::CanFrame> frames_;  // in file order, outliers left out
  std::vector<std::int64_t> play_ns_;  // per frame: its time on the playback axis (log_frame_times.hpp)
  can::CandumpCounters reader_counters_;
  bool end_missing_ = false;  // the gzip stream ended before its trailer
  std::uint64_t time_outlier_frames_ = 0;
  std::uint64_t time_steps_ = 0;
  std::size_t next_frame_ = 0;
  std::optional<std::int64_t> sample_step_ns_;
  std::int64_t loop_offset_ns_ = 0;  // added to every time in the loop being played

  boost::asio::steady_timer timer_;
  std::atomic<bool> finished_{false};
  std::atomic<std::uint64_t> frames_played_{0};
  std::atomic<std::uint64_t> loops_played_{0};
};

}  // namespace headingd::daemon
