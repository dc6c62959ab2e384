#pragma once
// The CAN IMU as a source: drivers/can's SocketCanReceiver on an io_context of its own
// thread, frames through the DBC-driven epoch assembler, each sample into the IMU ring.
// The kernel timestamps (CLOCK_REALTIME) are mapped to CLOCK_MONOTONIC as each sample is
// released: that is both the sample's time for the estimator and its arrival time, so the
// age at publish is measured from the frame's kernel timestamp.
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "headingd/can/can_config.hpp"
#include "headingd/can/dbc.hpp"
#include "headingd/can/epoch_assembler.hpp"
#include "headingd/can/imu_frame_codec.hpp"
#include "headingd/can/socketcan_receiver.hpp"
#include "headingd/daemon/ring_entries.hpp"
#include "headingd/daemon/sample_ring.hpp"
#include "headingd/daemon/source.hpp"

namespace headingd::daemon {

class CanImuSource final : public Source {
 public:
  // Reads the DBC file and checks the signal mapping (throws core::ConfigError).
  CanImuSource(std::string name, const can::CanConfig& config, std::uint16_t source_index,
               SampleRing<ImuRingEntry>* imu_ring);
  ~CanImuSource() override;

  const std::string& name() const override { return name_; }
  const char* kind() const override { return "can"; }
  void start() override;
  void stop() override;
  void report(SourceReport& out) const override;

 private:
  void onFrame(const can::CanFrame& frame);
  void pushSamples(const can::AssembledSamples& samples);
  void onTimer();  // flushes a stale epoch, copies the assembler's counters

  std::string name_;
  std::uint16_t source_index_;
  SampleRing<ImuRingEntry>* ring_;
  can::CanConfig config_;
  can::DbcDatabase dbc_;
  std::unique_ptr<can::ImuFrameCodec> codec_;
  std::unique_ptr<can::EpochAssembler> assembler_;
  std::int64_t flush_age_ns_ = 0;  // can_epoch_flush.hpp
  boost::asio::io_context io_;
  std::optional<boost::asio::executor_work_guard<boost::asio::io_context::executor_type>> work_;
  std::unique_ptr<can::SocketCanReceiver> receiver_;
  boost::asio::steady_timer timer_;
  std::thread thread_;
  std::atomic<std::uint64_t> pushed_{0}, dropped_{0};
  mutable std::mutex snapshot_mutex_;
  can::AssemblerCounters snapshot_;
};

}  // namespace headingd::daemon
