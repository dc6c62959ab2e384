#pragma once
// The CAN IMU as a source: drivers/can's SocketCanReceiver on an io_context of its own
// thread, frames through the DBC-driven epoch assembler, each sample into the IMU ring.
// Each frame's kernel timestamp (CLOCK_REALTIME) is put on CLOCK_MONOTONIC in whole
// microseconds as the frame arrives, before the assembler sees it: a sample's time (its first
// frame's) is then both its time for the estimator and its arrival time, so the age at
// publish is measured from the kernel timestamp; and the black box's candump lines, which
// have microseconds, hold exactly the times the assembler used.
#include <atomic>
#include <memory>

#include "headingd/can/can_config.hpp"
#include "headingd/can/dbc.hpp"
#include "headingd/can/epoch_assembler.hpp"
#include "headingd/can/imu_frame_codec.hpp"
#include "headingd/can/socketcan_receiver.hpp"
#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/sources/asio_source.hpp"
#include "headingd/daemon/sources/can_assembler_report.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/daemon/sources/wall_to_monotonic.hpp"
#include "headingd/recording/stream_recorders.hpp"

namespace headingd::daemon {

// [can], read by drivers/can's own loader (can_config.hpp); a present table is enabled.
// [can], read by drivers/can's own loader; a [can] table is a CAN source.
struct CanSourceConfig : SourceConfig {
  explicit CanSourceConfig(can::CanConfig settings) : can(std::move(settings)) { enabled = true; }
  can::CanConfig can;
  std::unique_ptr<Source> createSource(SourceContext& context) const override;
  std::vector<RecordedInputFile> recordedInputFiles() const override;  // the DBC
};
std::unique_ptr<SourceConfig> parseCanSource(const SourceTable& table);

class CanImuSource final : public AsioSource<can::AssemblerCounters> {
 public:
  // Reads the DBC file and checks the signal mapping (throws core::ConfigError).
  CanImuSource(std::string name, const can::CanConfig& config, std::uint16_t source_index,
               SampleRing<ImuRingEntry>* imu_ring, const RecorderSinks* recorder = nullptr);
  ~CanImuSource() override;

  const char* kind() const override { return "can"; }
  bool readsAtRealTimePace() const override { return true; }
  void report(SourceReport& out) const override;

 private:
  void onStart() override { receiver_->start(); }
  void onStop() override { receiver_->stop(); }
  void onTick() override;  // flushes a stale epoch
  can::AssemblerCounters currentCounters() const override { return assembler_->counters(); }
  void onFrame(const can::CanFrame& frame, std::int64_t kernel_realtime_ns);
  void pushSamples(const can::AssembledSamples& samples);

  SampleRing<ImuRingEntry>* ring_;
  can::CanConfig config_;
  can::DbcDatabase dbc_;
  std::unique_ptr<can::ImuFrameCodec> codec_;
  std::unique_ptr<can::EpochAssembler> assembler_;
  FullScaleWarning full_scale_warning_;
  std::int64_t flush_age_ns_ = 0;  // can/epoch_flush.hpp
  std::unique_ptr<can::SocketCanReceiver> receiver_;
  std::unique_ptr<recording::CanStreamRecorder> recorder_;  // null: not recording
  WallToMonotonic wall_to_mono_;                            // io thread; its counts for STATUS below
  std::atomic<std::uint64_t> clock_steps_{0}, future_stamps_{0};
};

}  // namespace headingd::daemon
