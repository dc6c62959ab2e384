#include "headingd/daemon/sources/can_imu_source.hpp"

#include <spdlog/spdlog.h>

#include "headingd/can/can_config_toml.hpp"
#include "headingd/can/epoch_flush.hpp"
#include "headingd/daemon/sources/can_assembler_report.hpp"
#include "headingd/files/input_file.hpp"
#include "headingd/live/clocks.hpp"
#include "headingd/recording/recording_format.hpp"

namespace headingd::daemon {
namespace {
// How often the open epoch is checked (can/epoch_flush.hpp says when it is given up on) and
// the counters are copied for STATUS.
constexpr auto kTimerPeriod = std::chrono::milliseconds(10);

std::int64_t wholeMicroseconds(std::int64_t ns) { return ns - ns % 1000; }
}  // namespace

std::unique_ptr<SourceConfig> parseCanSource(const SourceTable& table) {
  return std::make_unique<CanSourceConfig>(can::parseCanTable(table.table, table.source, table.base_dir));
}

std::unique_ptr<Source> CanSourceConfig::createSource(SourceContext& context) const {
  auto source =
      std::make_unique<CanImuSource>(table, can, context.source_index, context.addImuRing(table), context.recorder);
  spdlog::info("source can: interface {}, DBC {}", can.interface, can.dbc_path);
  return source;
}

std::vector<RecordedInputFile> CanSourceConfig::recordedInputFiles() const {
  return {{"dbc", can.dbc_path, recording::kDbcFile, files::kDbcFileLimit}};
}

CanImuSource::CanImuSource(std::string name, const can::CanConfig& config, std::uint16_t source_index,
                           SampleRing<ImuRingEntry>* imu_ring, const RecorderSinks* recorder)
    : AsioSource(std::move(name), source_index, Lifetime::kUntilStopped, kTimerPeriod),
      ring_(imu_ring),
      config_(config),
      dbc_(can::loadDbcFile(config.dbc_path)) {
  codec_ = std::make_unique<can::ImuFrameCodec>(config_, dbc_);
  assembler_ = std::make_unique<can::EpochAssembler>(*codec_, can::epochSettingsFrom(config_));
  flush_age_ns_ = can::epochFlushAgeNs(config_, *codec_);
  receiver_ = std::make_unique<can::SocketCanReceiver>(
      io(), can::receiverSettingsFrom(config_, *codec_),
      [this](const can::CanFrame& f, std::int64_t kernel_realtime_ns) { onFrame(f, kernel_realtime_ns); });
  if (recorder != nullptr && recorder->can != nullptr) {
    recorder_ =
        std::make_unique<recording::CanStreamRecorder>(*recorder->can, config_.interface, recorder->can_time_offset_ns);
  }
}

CanImuSource::~CanImuSource() { stop(); }

void CanImuSource::pushSamples(const can::AssembledSamples& samples) {
  for (int i = 0; i < samples.count; ++i) {
    ImuRingEntry e;
    e.sample = samples.samples[static_cast<std::size_t>(i)];
    e.arrival_mono_ns = e.sample.t_ns;
    if (!push(*ring_, e) && recorder_ != nullptr) recorder_->dropped(e.sample.t_ns);
  }
}

void CanImuSource::onFrame(const can::CanFrame& received, std::int64_t kernel_realtime_ns) {
  // The offset is read now, microseconds after the frame; a wall-clock step in between is
  // undone by wall_to_monotonic.hpp.
  can::CanFrame frame = received;
  const ClockReading now = readClocks(live::monotonicNs, live::realtimeNs);
  const std::int64_t t = kernel_realtime_ns != 0 ? wall_to_mono_.map(kernel_realtime_ns, now)
                                                 : now.monotonic_ns;  // no kernel timestamp: the best we know
  clock_steps_.store(wall_to_mono_.steps(), std::memory_order_relaxed);
  future_stamps_.store(wall_to_mono_.clamped(), std::memory_order_relaxed);
  frame.t_ns = wholeMicroseconds(t);
  if (recorder_ != nullptr) recorder_->frame(frame);
  pushSamples(assembler_->push(frame));
  full_scale_warning_.look(assembler_->counters(), now.monotonic_ns, "can");
}

void CanImuSource::onTick() {
  const std::int64_t now = wholeMicroseconds(live::monotonicNs());
  const bool was_open = assembler_->hasOpenEpoch();
  const can::AssembledSamples samples = can::flushEpoch(*assembler_, config_, flush_age_ns_, now);
  // Only a flush that closed an epoch changes anything, so only that one is recorded.
  if (recorder_ != nullptr && was_open && !assembler_->hasOpenEpoch()) recorder_->flushed(now);
  pushSamples(samples);
}

void CanImuSource::report(SourceReport& out) const {
  const can::ReceiverStatus r = receiver_->status();
  switch (r.state) {
    case can::LinkState::up: out.state = SourceState::kRunning; break;
    case can::LinkState::down:
    case can::LinkState::waiting: out.state = SourceState::kWaiting; break;
  }
  out.setLastError(r.last_error);
  std::size_t i = reportPushes(out, "samples_pushed");
  out.set(i++, "frames", r.frames);
  out.set(i++, "kernel_drops", r.kernel_drops);
  out.set(i++, "read_errors", r.read_errors);
  out.set(i++, "open_failures", r.open_failures);
  out.set(i++, "times_up", r.times_up);
  out.set(i++, "times_lost", r.times_lost);
  out.set(i++, "bus_error_frames", r.bus.error_frames);
  out.set(i++, "bus_off", r.bus.bus_off);
  out.set(i++, "error_passive", r.bus.error_passive);
  out.set(i++, "controller_rx_overflow", r.bus.controller_rx_overflow);
  out.set(i++, "protocol_violations", r.bus.protocol_violations);
  out.set(i++, "wall_clock_steps", clock_steps_.load(std::memory_order_relaxed));
  out.set(i++, "future_timestamps", future_stamps_.load(std::memory_order_relaxed));
  withSnapshot([&](const can::AssemblerCounters& assembler) { reportAssemblerCounters(out, &i, assembler); });
}

}  // namespace headingd::daemon
