#include "headingd/daemon/sources/gpsd_gps_source.hpp"

#include <spdlog/spdlog.h>

#include "headingd/live/clocks.hpp"

namespace headingd::daemon {
std::unique_ptr<Source> GpsdGpsSourceConfig::createSource(SourceContext& context) const {
  auto source = std::make_unique<GpsdGpsSource>(table, gpsd, context.source_index, context.addGpsRing(table));
  spdlog::info("source gps: gpsd at {}:{}", gpsd.host, gpsd.port);
  if (context.recorder != nullptr && context.recorder->gps != nullptr) {
    // The black box's GPS stream is the receiver's NMEA, which gpsd does not pass on.
    spdlog::warn("gps: the black box does not record gpsd's reports; a replay of this recording has no GPS");
  }
  return source;
}

GpsdGpsSource::GpsdGpsSource(std::string name, const gpsd::GpsdConfig& config, std::uint16_t source_index,
                             SampleRing<GpsRingEntry>* gps_ring)
    : GpsFixSource(std::move(name), source_index, gps_ring) {
  driver_ = std::make_unique<gpsd::GpsdClient>(
      io(), config, [this](const nmea::Fix& fix, std::int64_t receive_ns) { pushFix(fix, receive_ns); },
      [this](std::string_view kind, const std::string& detail) { onProblem(kind, detail); });
}

GpsdGpsSource::~GpsdGpsSource() { stop(); }

void GpsdGpsSource::onProblem(std::string_view kind, const std::string& detail) {
  std::uint64_t suppressed = 0;
  if (!problem_log_.allow(live::monotonicNs(), &suppressed)) return;
  if (suppressed > 0) {
    spdlog::warn("gps: gpsd line {}: {} ({} more not logged)", kind, detail, suppressed);
  } else {
    spdlog::warn("gps: gpsd line {}: {}", kind, detail);
  }
}

void GpsdGpsSource::report(SourceReport& out) const {
  withSnapshot([&](const gpsd::GpsdCounters& c) {
    switch (c.state) {
      case gpsd::GpsdState::kConnected: out.state = SourceState::kRunning; break;
      case gpsd::GpsdState::kConnecting: out.state = SourceState::kStarting; break;
      case gpsd::GpsdState::kWaiting: out.state = SourceState::kWaiting; break;
      case gpsd::GpsdState::kStopped: out.state = SourceState::kStarting; break;
    }
    out.setLastError(c.last_error);
    std::size_t i = reportPushes(out, "epochs_pushed");
    gpsd::forEachCounter(c, [&](const char* name, std::uint64_t v) { out.set(i++, name, v); });
  });
}

}  // namespace headingd::daemon
