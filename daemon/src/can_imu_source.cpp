#include "headingd/daemon/can_imu_source.hpp"

#include <spdlog/spdlog.h>

#include "headingd/can/can_config_toml.hpp"
#include "headingd/daemon/can_assembler_report.hpp"
#include "headingd/daemon/can_epoch_flush.hpp"
#include "headingd/daemon/clocks.hpp"

namespace headingd::daemon {
namespace {
// How often the open epoch is checked (can_epoch_flush.hpp says when it is given up on) and
// the counters are copied for STATUS.
constexpr auto kTimerPeriod = std::chrono::milliseconds(10);
}  // namespace

std::unique_ptr<SourceConfig> parseCanSource(const SourceTable& table) {
  auto config = std::make_unique<CanSourceConfig>();
  config->can = can::parseCanTable(table.table, table.source, table.base_dir);
  config->enabled = true;
  return config;
}

std::unique_ptr<Source> createCanSource(const SourceConfig& config, SourceContext& context) {
  const can::CanConfig& can = static_cast<const CanSourceConfig&>(config).can;
  auto source = std::make_unique<CanImuSource>(config.table, can, context.source_index, context.addImuRing(config.table));
  spdlog::info("source can: interface {}, DBC {}", can.interface, can.dbc_path);
  return source;
}

CanImuSource::CanImuSource(std::string name, const can::CanConfig& config, std::uint16_t source_index,
                           SampleRing<ImuRingEntry>* imu_ring)
    : AsioSource(std::move(name), source_index, Lifetime::kUntilStopped, kTimerPeriod),
      ring_(imu_ring),
      config_(config),
      dbc_(can::loadDbcFile(config.dbc_path)) {
  codec_ = std::make_unique<can::ImuFrameCodec>(config_, dbc_);
  assembler_ = std::make_unique<can::EpochAssembler>(*codec_, can::epochSettingsFrom(config_));
  flush_age_ns_ = epochFlushAgeNs(config_, *codec_);
  receiver_ = std::make_unique<can::SocketCanReceiver>(io(), can::receiverSettingsFrom(config_, *codec_),
                                                      [this](const can::CanFrame& f) { onFrame(f); });
}

CanImuSource::~CanImuSource() { stop(); }

void CanImuSource::pushSamples(const can::AssembledSamples& samples) {
  if (samples.count == 0) return;
  // Kernel timestamps are CLOCK_REALTIME; the estimator's axis is CLOCK_MONOTONIC. The
  // offset is read now, microseconds after the frame, so a wall-clock step moves at most
  // the samples released across it.
  const std::int64_t realtime_minus_monotonic = realtimeNs() - monotonicNs();
  for (int i = 0; i < samples.count; ++i) {
    ImuRingEntry e;
    e.sample = samples.samples[static_cast<std::size_t>(i)];
    if (e.sample.t_ns != 0) {
      e.sample.t_ns -= realtime_minus_monotonic;
    } else {
      e.sample.t_ns = monotonicNs();  // no kernel timestamp: the best we know
    }
    e.arrival_mono_ns = e.sample.t_ns;
    push(*ring_, e);
  }
}

void CanImuSource::onFrame(const can::CanFrame& frame) { pushSamples(assembler_->push(frame)); }

void CanImuSource::onTick() { pushSamples(flushEpoch(*assembler_, config_, flush_age_ns_, realtimeNs())); }

void CanImuSource::report(SourceReport& out) const {
  const can::ReceiverStatus r = receiver_->status();
  switch (r.state) {
    case can::LinkState::up: out.state = SourceState::kRunning; break;
    case can::LinkState::down:
    case can::LinkState::waiting: out.state = SourceState::kWaiting; break;
  }
  if (out.last_error != r.last_error) out.last_error = r.last_error;
  std::size_t i = 0;
  out.set(i++, "samples_pushed", pushed());
  out.set(i++, "ring_full_drops", ringFullDrops());
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
  withSnapshot([&](const can::AssemblerCounters& assembler) { reportAssemblerCounters(out, &i, assembler); });
}

}  // namespace headingd::daemon
