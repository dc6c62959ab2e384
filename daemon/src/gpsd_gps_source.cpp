#include "headingd/daemon/gpsd_gps_source.hpp"

#include <time.h>

#include <spdlog/spdlog.h>

#include "headingd/nmea/gps_observation_from_fix.hpp"

namespace headingd::daemon {
namespace {
// How often the client's counters are copied for STATUS (they may only be read on its thread).
constexpr auto kSnapshotPeriod = std::chrono::milliseconds(250);

std::int64_t monotonicNowNs() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}
}  // namespace

std::unique_ptr<SourceConfig> parseGpsdGpsSource(const SourceTable& table) {
  auto config = std::make_unique<GpsdGpsSourceConfig>();
  config->gpsd = gpsd::parseGpsdTable(&table.table, table.source);
  config->enabled = config->gpsd.enabled;
  return config;
}

std::unique_ptr<Source> createGpsdGpsSource(const SourceConfig& config, SourceContext& context) {
  const gpsd::GpsdConfig& g = static_cast<const GpsdGpsSourceConfig&>(config).gpsd;
  auto source =
      std::make_unique<GpsdGpsSource>(config.table, g, context.source_index, context.addGpsRing(config.table));
  spdlog::info("source gps: gpsd at {}:{}", g.host, g.port);
  if (context.recorder != nullptr && context.recorder->gps != nullptr) {
    // The black box's GPS stream is the receiver's NMEA, which gpsd does not pass on.
    spdlog::warn("gps: the black box does not record gpsd's reports; a replay of this recording has no GPS");
  }
  return source;
}

GpsdGpsSource::GpsdGpsSource(std::string name, const gpsd::GpsdConfig& config, std::uint16_t source_index,
                             SampleRing<GpsRingEntry>* gps_ring)
    : AsioSource(std::move(name), source_index, Lifetime::kUntilStopped, kSnapshotPeriod), ring_(gps_ring) {
  client_ = std::make_unique<gpsd::GpsdClient>(
      io(), config, [this](const nmea::Fix& fix, std::int64_t receive_ns) { onFix(fix, receive_ns); },
      [this](std::string_view kind, const std::string& detail) { onProblem(kind, detail); });
}

GpsdGpsSource::~GpsdGpsSource() { stop(); }

void GpsdGpsSource::onStop() {
  client_->stop();
  takeSnapshot();  // the client's last word, for a report after stop
}

void GpsdGpsSource::onFix(const nmea::Fix& fix, std::int64_t receive_ns) {
  GpsRingEntry e;
  e.observation = nmea::gpsObservationFromFix(fix, receive_ns);
  e.arrival_mono_ns = receive_ns;
  push(*ring_, e);
}

void GpsdGpsSource::onProblem(std::string_view kind, const std::string& detail) {
  std::uint64_t suppressed = 0;
  if (!problem_log_.allow(monotonicNowNs(), &suppressed)) return;
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
    if (out.last_error != c.last_error) out.last_error = c.last_error;
    std::size_t i = 0;
    out.set(i++, "epochs_pushed", pushed());
    out.set(i++, "ring_full_drops", ringFullDrops());
    out.set(i++, "epochs", c.epochs);
    out.set(i++, "late_reports", c.late_reports);
    out.set(i++, "bytes", c.lines.bytes);
    out.set(i++, "lines", c.lines.lines);
    out.set(i++, "oversized_lines", c.lines.oversized);
    out.set(i++, "cut_lines", c.lines.cut);
    out.set(i++, "tpv_reports", c.tpv_reports);
    out.set(i++, "sky_reports", c.sky_reports);
    out.set(i++, "other_reports", c.other_reports);
    out.set(i++, "malformed", c.malformed);
    out.set(i++, "missing_fields", c.missing_fields);
    out.set(i++, "connect_attempts", c.connect_attempts);
    out.set(i++, "connect_failures", c.connect_failures);
    out.set(i++, "connects", c.connects);
    out.set(i++, "disconnects", c.disconnects);
  });
}

}  // namespace headingd::daemon
