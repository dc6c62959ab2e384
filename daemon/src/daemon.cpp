#include "headingd/daemon/daemon.hpp"

#include <spdlog/spdlog.h>

#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/daemon/imu_csv_source.hpp"
#ifdef HEADINGD_WITH_CAN
#include "headingd/daemon/can_imu_source.hpp"
#include "headingd/daemon/candump_log_source.hpp"
#endif
#ifdef HEADINGD_WITH_GPS_SERIAL
#include "headingd/daemon/nmea_log_source.hpp"
#include "headingd/daemon/serial_gps_source.hpp"
#endif
#include "headingd/daemon/clocks.hpp"
#include "headingd/daemon/realtime.hpp"
#include "headingd/files/numeric_csv.hpp"

namespace headingd::daemon {

Daemon::Daemon(DaemonConfig config) : config_(std::move(config)) {
  if (!config_.wmm_path.empty()) {
    wmm_ = std::make_unique<core::WorldMagneticModel>(
        core::parseWmmCoefficients(files::readMaybeGzipFile(config_.wmm_path), config_.wmm_path));
  }
  // Each source gets its own rings (single producer each); see daemon/README.md, "Sources".
#ifdef HEADINGD_WITH_CAN
  if (config_.can) {
    const auto index = static_cast<std::uint16_t>(sources_.size());
    imu_rings_.push_back(std::make_unique<SampleRing<ImuRingEntry>>("can.imu", config_.imu_ring_capacity));
    sources_.push_back(std::make_unique<CanImuSource>("can", *config_.can, index, imu_rings_.back().get()));
    spdlog::info("source can: interface {}, DBC {}", config_.can->interface, config_.can->dbc_path);
  }
#endif
#ifdef HEADINGD_WITH_GPS_SERIAL
  if (config_.gps && config_.gps->enabled) {
    const auto index = static_cast<std::uint16_t>(sources_.size());
    gps_rings_.push_back(std::make_unique<SampleRing<GpsRingEntry>>("gps.gps", config_.gps_ring_capacity));
    sources_.push_back(std::make_unique<SerialGpsSource>("gps", *config_.gps, index, gps_rings_.back().get()));
    spdlog::info("source gps: {} at {} baud", config_.gps->device, config_.gps->baud);
  }
#endif
  if (config_.imu_csv.enabled) {
    const auto index = static_cast<std::uint16_t>(sources_.size());
    imu_rings_.push_back(std::make_unique<SampleRing<ImuRingEntry>>("imu_csv.imu", config_.imu_ring_capacity));
    SampleRing<GpsRingEntry>* gps_ring = nullptr;
    if (!config_.imu_csv.nmea_path.empty()) {
      gps_rings_.push_back(std::make_unique<SampleRing<GpsRingEntry>>("imu_csv.gps", config_.gps_ring_capacity));
      gps_ring = gps_rings_.back().get();
    }
    auto source = std::make_unique<ImuCsvSource>("imu_csv", config_.imu_csv, index, imu_rings_.back().get(), gps_ring);
    spdlog::info("source imu_csv: {} ({} samples{}), speed {}x, at end: {}", config_.imu_csv.imu_csv_path,
                 source->imuSampleCount(),
                 config_.imu_csv.nmea_path.empty() ? std::string()
                                                   : ", GPS " + config_.imu_csv.nmea_path + " (" +
                                                         std::to_string(source->gpsEpochCount()) + " epochs)",
                 config_.imu_csv.speed, atEndName(config_.imu_csv.at_end));
    sources_.push_back(std::move(source));
  }
  addLogSources();
  if (sources_.empty()) spdlog::warn("no source is configured: STATUS will say degraded (no IMU data)");
}

void Daemon::addLogSources() {
  // [candump_log] and [nmea_log] play on one clock, which starts at the earliest first
  // timestamp of the two logs (playback_clock.hpp).
  playback_clock_.speed = config_.playback.speed;
  std::optional<std::int64_t> log_t0;
  auto earliest = [&log_t0](std::optional<std::int64_t> t) {
    if (t && (!log_t0 || *t < *log_t0)) log_t0 = t;
  };
#ifdef HEADINGD_WITH_CAN
  if (config_.candump_log.enabled) {
    const auto index = static_cast<std::uint16_t>(sources_.size());
    imu_rings_.push_back(std::make_unique<SampleRing<ImuRingEntry>>("candump_log.imu", config_.imu_ring_capacity));
    auto source = std::make_unique<CandumpLogSource>("candump_log", config_.candump_log, *config_.candump_log_can,
                                                     config_.playback.at_end, &playback_clock_, index,
                                                     imu_rings_.back().get());
    spdlog::info("source candump_log: {} ({} frames), decoded by {} (DBC {})", config_.candump_log.path,
                 source->frameCount(), config_.candump_log.can_config_path, config_.candump_log_can->dbc_path);
    earliest(source->firstLogNs());
    sources_.push_back(std::move(source));
  }
#endif
#ifdef HEADINGD_WITH_GPS_SERIAL
  if (config_.nmea_log.enabled) {
    const auto index = static_cast<std::uint16_t>(sources_.size());
    gps_rings_.push_back(std::make_unique<SampleRing<GpsRingEntry>>("nmea_log.gps", config_.gps_ring_capacity));
    auto source = std::make_unique<NmeaLogSource>("nmea_log", config_.nmea_log, config_.playback, &playback_clock_,
                                                  index, gps_rings_.back().get());
    spdlog::info("source nmea_log: {} ({} epochs)", config_.nmea_log.path, source->epochCount());
    earliest(source->firstLogNs());
    sources_.push_back(std::move(source));
  }
#endif
  playback_clock_.log_t0_ns = log_t0.value_or(0);
  if (config_.candump_log.enabled || config_.nmea_log.enabled) {
    spdlog::info("log playback: speed {}x, start delay {} s, at end: {}", config_.playback.speed,
                 config_.playback.start_delay_s, atEndName(config_.playback.at_end));
  }
}

Daemon::~Daemon() { stop(); }

void Daemon::start() {
  applyMemoryLock(config_.realtime);
  publisher_ = std::make_unique<LcmPublisher>(config_.lcm.url);
  if (config_.lcm.url.rfind("udpm://", 0) == 0 && config_.lcm.url.find("ttl=0") == std::string::npos) {
    spdlog::warn("LCM URL {} has no ttl=0: messages may leave this machine", config_.lcm.url);
  }
  std::vector<SampleRing<ImuRingEntry>*> imu;
  for (auto& r : imu_rings_) imu.push_back(r.get());
  std::vector<SampleRing<GpsRingEntry>*> gps;
  for (auto& r : gps_rings_) gps.push_back(r.get());
  std::vector<Source*> sources;
  for (auto& s : sources_) sources.push_back(s.get());
  loop_ = std::make_unique<EstimatorLoop>(config_, wmm_.get(), imu, gps, sources, *publisher_, notifier_);
  loop_thread_ = std::thread([this] { loop_->run(); });
  // Read by the log sources from their own threads, which start below.
  playback_clock_.start_mono_ns = monotonicNs() + std::llround(config_.playback.start_delay_s * 1e9);
  for (auto& s : sources_) s->start();
  sources_started_ = true;
  spdlog::info("running: estimator at {} Hz, LCM {} (channels {}, {}, {}, {}, {}){}", config_.rate_hz,
               config_.lcm.url, config_.lcm.heading_channel, config_.lcm.attitude_channel, config_.lcm.imu_channel,
               config_.lcm.gps_channel, config_.lcm.status_channel,
               notifier_.underSystemd() ? ", under systemd" : "");
  if (notifier_.watchdogIntervalUs() != 0) {
    spdlog::info("systemd watchdog every {:.1f} s, pinged from the estimator loop",
                 static_cast<double>(notifier_.watchdogIntervalUs()) * 1e-6);
  }
}

void Daemon::stop() {
  if (sources_started_) {
    notifier_.stopping();
    for (auto& s : sources_) s->stop();
    sources_started_ = false;
  }
  if (loop_ != nullptr) loop_->stop();
  if (loop_thread_.joinable()) loop_thread_.join();
}

void Daemon::requestCalibrationReload() {
  if (loop_ != nullptr) loop_->requestCalibrationReload();
}

LoopSummary Daemon::summary() const { return loop_ != nullptr ? loop_->summary() : LoopSummary{}; }

}  // namespace headingd::daemon
