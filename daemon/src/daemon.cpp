#include "headingd/daemon/daemon.hpp"

#include <spdlog/spdlog.h>

#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/daemon/clocks.hpp"
#include "headingd/daemon/realtime.hpp"
#include "headingd/daemon/source_registry.hpp"
#include "headingd/files/numeric_csv.hpp"

namespace headingd::daemon {

Daemon::Daemon(DaemonConfig config) : config_(std::move(config)) {
  if (!config_.wmm_path.empty()) {
    wmm_ = std::make_unique<core::WorldMagneticModel>(
        core::parseWmmCoefficients(files::readMaybeGzipFile(config_.wmm_path), config_.wmm_path));
  }
  // Each source gets its own rings (single producer each); see daemon/README.md, "Sources".
  const SourceConfigs& configs = config_.sources;
  SourceContext context{config_.imu_ring_capacity, config_.gps_ring_capacity, imu_rings_, gps_rings_,
                        configs.playback, &playback_clock_, 0, std::nullopt};
  sources_ = makeSources(configs, context);
  // The log sources play on one clock, which starts at the earliest first timestamp of the
  // logs (playback_clock.hpp).
  playback_clock_.speed = configs.playback.speed;
  playback_clock_.log_t0_ns = context.log_t0_ns.value_or(0);
  if (usesLogClock(configs)) {
    spdlog::info("log playback: speed {}x, start delay {} s, at end: {}", configs.playback.speed,
                 configs.playback.start_delay_s, atEndName(configs.playback.at_end));
  }
  if (sources_.empty()) spdlog::warn("no source is configured: STATUS will say degraded (no IMU data)");
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
  playback_clock_.start_mono_ns = monotonicNs() + std::llround(config_.sources.playback.start_delay_s * 1e9);
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
