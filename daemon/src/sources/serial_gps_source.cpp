#include "headingd/daemon/sources/serial_gps_source.hpp"

#include <spdlog/spdlog.h>

namespace headingd::daemon {
std::unique_ptr<Source> SerialGpsSourceConfig::createSource(SourceContext& context) const {
  auto source =
      std::make_unique<SerialGpsSource>(table, gps, context.source_index, context.addGpsRing(table), context.recorder);
  spdlog::info("source gps: {} at {} baud", gps.device, gps.baud);
  return source;
}

SerialGpsSource::SerialGpsSource(std::string name, const nmea::SerialGpsConfig& config, std::uint16_t source_index,
                                 SampleRing<GpsRingEntry>* gps_ring, const RecorderSinks* recorder)
    : GpsFixSource(std::move(name), source_index, gps_ring) {
  driver_ = std::make_unique<nmea::SerialGpsReader>(
      io(), config, [this](const nmea::Fix& fix, std::int64_t receive_ns) { pushFix(fix, receive_ns); });
  if (recorder != nullptr && recorder->gps != nullptr) {
    recorder_ = std::make_unique<recording::GpsStreamRecorder>(*recorder->gps);
    driver_->setInputTap(recorder_.get());
  }
}

SerialGpsSource::~SerialGpsSource() { stop(); }

void SerialGpsSource::report(SourceReport& out) const {
  withSnapshot([&](const nmea::SerialGpsCounters& c) {
    switch (c.state) {
      case nmea::SerialGpsState::kOpen: out.state = SourceState::kRunning; break;
      case nmea::SerialGpsState::kWaitingForDevice: out.state = SourceState::kWaiting; break;
      case nmea::SerialGpsState::kBusy: out.state = SourceState::kWaiting; break;  // last_error names the holder
      case nmea::SerialGpsState::kError: out.state = SourceState::kError; break;
      case nmea::SerialGpsState::kStopped: out.state = SourceState::kStarting; break;
    }
    out.setLastError(c.last_error);
    std::size_t i = reportPushes(out, "epochs_pushed");
    nmea::forEachCounter(c, [&](const char* name, std::uint64_t v) { out.set(i++, name, v); });
    nmea::forEachCounter(c.parser, [&](const char* name, std::uint64_t v) { out.set(i++, "nmea_", name, v); });
  });
}

}  // namespace headingd::daemon
