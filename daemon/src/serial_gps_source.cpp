#include "headingd/daemon/serial_gps_source.hpp"

#include <spdlog/spdlog.h>

#include "headingd/nmea/gps_observation_from_fix.hpp"

namespace headingd::daemon {
namespace {
// How often the reader's counters are copied for STATUS (they may only be read on its thread).
constexpr auto kSnapshotPeriod = std::chrono::milliseconds(250);
}  // namespace

std::unique_ptr<SourceConfig> parseSerialGpsSource(const SourceTable& table) {
  auto config = std::make_unique<SerialGpsSourceConfig>();
  config->gps = nmea::parseGpsTable(&table.table, table.source);
  config->enabled = config->gps.enabled;
  return config;
}

std::unique_ptr<Source> createSerialGpsSource(const SourceConfig& config, SourceContext& context) {
  const nmea::SerialGpsConfig& gps = static_cast<const SerialGpsSourceConfig&>(config).gps;
  auto source = std::make_unique<SerialGpsSource>(config.table, gps, context.source_index,
                                                  context.addGpsRing(config.table), context.recorder);
  spdlog::info("source gps: {} at {} baud", gps.device, gps.baud);
  return source;
}

SerialGpsSource::SerialGpsSource(std::string name, const nmea::SerialGpsConfig& config, std::uint16_t source_index,
                                 SampleRing<GpsRingEntry>* gps_ring, const RecorderSinks* recorder)
    : AsioSource(std::move(name), source_index, Lifetime::kUntilStopped, kSnapshotPeriod), ring_(gps_ring) {
  reader_ = std::make_unique<nmea::SerialGpsReader>(
      io(), config, [this](const nmea::Fix& fix, std::int64_t receive_ns) { onFix(fix, receive_ns); });
  if (recorder != nullptr && recorder->gps != nullptr) {
    recorder_ = std::make_unique<recording::GpsStreamRecorder>(*recorder->gps);
    reader_->setInputTap(recorder_.get());
  }
}

SerialGpsSource::~SerialGpsSource() { stop(); }

void SerialGpsSource::onStop() {
  reader_->stop();
  takeSnapshot();  // the reader's last word, for a report after stop
}

void SerialGpsSource::onFix(const nmea::Fix& fix, std::int64_t receive_ns) {
  GpsRingEntry e;
  e.observation = nmea::gpsObservationFromFix(fix, receive_ns);
  e.arrival_mono_ns = receive_ns;
  push(*ring_, e);
}

void SerialGpsSource::report(SourceReport& out) const {
  withSnapshot([&](const nmea::SerialGpsCounters& c) {
    switch (c.state) {
      case nmea::SerialGpsState::kOpen: out.state = SourceState::kRunning; break;
      case nmea::SerialGpsState::kWaitingForDevice: out.state = SourceState::kWaiting; break;
      case nmea::SerialGpsState::kBusy: out.state = SourceState::kWaiting; break;  // last_error names the holder
      case nmea::SerialGpsState::kError: out.state = SourceState::kError; break;
      case nmea::SerialGpsState::kStopped: out.state = SourceState::kStarting; break;
    }
    if (out.last_error != c.last_error) out.last_error = c.last_error;
    std::size_t i = 0;
    out.set(i++, "epochs_pushed", pushed());
    out.set(i++, "ring_full_drops", ringFullDrops());
    out.set(i++, "epochs", c.epochs.epochs);
    out.set(i++, "reads", c.reads);
    out.set(i++, "read_errors", c.read_errors);
    out.set(i++, "disconnects", c.disconnects);
    out.set(i++, "open_attempts", c.open_attempts);
    out.set(i++, "reopens", c.reopens);
    out.set(i++, "port_busy", c.port_busy);
    nmea::forEachCounter(c.parser, [&](const char* name, std::uint64_t v) { out.set(i++, "nmea_", name, v); });
  });
}

}  // namespace headingd::daemon
