#include "headingd/daemon/daemon.hpp"

#include <pthread.h>
#include <spdlog/spdlog.h>

#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/daemon/recorder/recording_files.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/daemon/system/realtime.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/live/clocks.hpp"
#include "headingd/recording/recording_format.hpp"

namespace headingd::daemon {
namespace {

// A recorder stream as the sources' line sink (it refuses lines until the recorder started).
class RecorderLineSink final : public recording::LineSink {
 public:
  explicit RecorderLineSink(RecorderStream& stream) : stream_(stream) {}
  bool write(std::string_view line) override { return stream_.write(line); }

 private:
  RecorderStream& stream_;
};

}  // namespace

void Daemon::usePlace() {
  core::ConfiguredPlace& place = *config_.place;
  std::string warning;
  try {
    place.decimal_year = core::placeDecimalYear(place, core::decimalYearOfUnixNs(live::realtimeNs()), *wmm_, &warning);
  } catch (const core::ConfigError& e) {
    throw core::ConfigError(config_.source + ": " + e.what());
  }
  if (!warning.empty()) spdlog::warn("[place]: {}", warning);
  spdlog::info("{}", core::describePlace(place.position, *place.decimal_year, *wmm_));
}

void Daemon::seedGpsDate() {
  // The system clock is today's date only for live sources (files carry their own dates), and
  // [place] has given one already.
  if (config_.gps_date_seed || config_.place || wmm_ == nullptr || !hasLiveSource(config_.sources)) return;
  const double today = core::decimalYearOfUnixNs(live::realtimeNs());
  if (!wmm_->isDateWithinValidity(today)) {
    spdlog::warn(
        "the system clock's date ({:.2f}) is outside {}'s validity: GPS dates are checked against the "
        "model's validity only",
        today, wmm_->modelName());
    return;
  }
  config_.gps_date_seed = today;
}

Daemon::Daemon(DaemonConfig config) : config_(std::move(config)) {
  calibration_ = loadCalibration(config_.calibration_path);
  if (!config_.wmm_path.empty()) {
    wmm_ = std::make_unique<core::WorldMagneticModel>(
        core::parseWmmCoefficients(files::readMaybeGzipFile(config_.wmm_path, files::kWmmFileLimit), config_.wmm_path));
  }
  if (config_.place) usePlace();
  seedGpsDate();
  // Each source gets its own rings (single producer each); see daemon/README.md, "Sources".
  const SourceConfigs& configs = config_.sources;
  makeRecorder();
  rings_.imu_capacity = config_.imu_ring_capacity;
  rings_.gps_capacity = config_.gps_ring_capacity;
  SourceContext context(rings_, configs.playback, &playback_clock_, recorder_ != nullptr ? &source_sinks_ : nullptr);
  sources_ = makeSources(configs, context);
  // The log sources play on one clock, which starts at the earliest first timestamp of the
  // logs (playback_clock.hpp).
  playback_clock_.speed = configs.playback.speed;
  playback_clock_.log_t0_ns = context.log_t0_ns.value_or(0);
  if (configs.playback.at_end == AtEnd::kLoop) playback_clock_.loop_ns = context.loopLengthNs();
  if (usesLogClock(configs)) {
    spdlog::info("log playback: speed {}x, start delay {} s, at end: {}{}", configs.playback.speed,
                 configs.playback.start_delay_s, atEndName(configs.playback.at_end),
                 playback_clock_.loop_ns > 0 ? fmt::format(" (a loop is {:.3f} s of log time)",
                                                           static_cast<double>(playback_clock_.loop_ns) * 1e-9)
                                             : std::string());
  }
  if (config_.nmea_out.enabled) {
    nmea_out_ =
        std::make_unique<NmeaOutServer>(config_.nmea_out, config_.log.repeat_burst, config_.log.repeat_interval_s);
  }
  if (sources_.empty()) spdlog::warn("no source is configured: STATUS will say degraded (no IMU data)");
}

Daemon::~Daemon() { stop(); }

void Daemon::makeRecorder() {
  const RecorderConfig& rc = config_.recorder;
  if (!hasLiveSource(config_.sources)) return;  // file sources: their files are the record
  if (!rc.enabled) {
    spdlog::info("black box off: {}", rc.off_reason.empty() ? "[recorder] enabled = false" : rc.off_reason);
    return;
  }
  recorder_ = std::make_unique<Recorder>(
      rc, std::vector<std::string>{std::string(recording::kCanStream), std::string(recording::kGpsStream),
                                   std::string(recording::kEstimatorStream)});
  for (const std::string_view stream : {recording::kCanStream, recording::kGpsStream, recording::kEstimatorStream}) {
    recorder_sinks_.push_back(std::make_unique<RecorderLineSink>(recorder_->stream(stream)));
  }
  source_sinks_.can = recorder_sinks_[0].get();
  source_sinks_.gps = recorder_sinks_[1].get();
  // The offset the CAN stream's candump times are written with, fixed before the sources are made.
  recording_start_ = recordingStartNow(HEADINGD_VERSION);
  source_sinks_.can_time_offset_ns = recording_start_.can_time_offset_ns;
}

void Daemon::startRecorder() {
  if (recorder_ == nullptr) return;
  try {
    recorder_->start(recordingFiles(config_, recording_start_));
    spdlog::info("black box: recording the inputs to {}", recorder_->folder());
  } catch (const std::exception& e) {
    spdlog::error("black box: not recording: {}", e.what());
  }
}

static_assert(kDefaultSendQueueBytes == LcmPublisher::kDefaultQueueBytes,
              "[lcm] send_queue_bytes defaults to the publisher's own queue size");

void Daemon::start() {
  realtime_ = std::make_unique<RealtimeSettings>(config_.realtime);
  realtime_->lockMemory();
  publisher_ = std::make_unique<LcmPublisher>(config_.lcm.url,
                                              RepeatLimiter(config_.log.repeat_burst, config_.log.repeat_interval_s),
                                              config_.lcm.send_queue_bytes);
  // A HEADING per IMU sample is asked for its latency: sent at once, on the estimator thread.
  publisher_->setSendInline(config_.publish_on_imu);
  publisher_->start([this] {
    pthread_setname_np(pthread_self(), "lcm-send");
    realtime_->applyToLcmSenderThread();
  });
  if (config_.lcm.url.rfind("udpm://", 0) == 0 && config_.lcm.url.find("ttl=0") == std::string::npos) {
    spdlog::warn("LCM URL {} has no ttl=0: messages may leave this machine", config_.lcm.url);
  }
  std::vector<SampleRing<ImuRingEntry>*> imu;
  for (auto& r : rings_.imu) imu.push_back(r.get());
  std::vector<SampleRing<GpsRingEntry>*> gps;
  for (auto& r : rings_.gps) gps.push_back(r.get());
  std::vector<Source*> sources;
  for (auto& s : sources_) sources.push_back(s.get());
  loop_ = std::make_unique<EstimatorLoop>(config_, wmm_.get(), imu, gps, sources, *publisher_, notifier_, *realtime_,
                                          std::move(calibration_));
  startRecorder();
  if (recorder_ != nullptr) {
    recorder_output_ = std::make_unique<RecorderOutput>(*recorder_sinks_[2], *recorder_);
    loop_->addSink(recorder_output_.get());
  }
  if (nmea_out_ != nullptr) {
    nmea_out_->start();  // a port that is taken stops start-up here (exit status 1)
    // Files are a replay: THS says S (simulator) for them.
    nmea_output_ =
        std::make_unique<NmeaOutput>(config_.nmea_out, config_.rate_hz, *nmea_out_, !hasLiveSource(config_.sources));
    loop_->addSink(nmea_output_.get());
  }
  if (config_.publish_on_imu) {
    for (auto& r : rings_.imu) r->setDoorbell(&doorbell_);
    loop_->setDoorbell(&doorbell_);
  }
  loop_thread_ = std::thread([this] { loop_->run(); });
  // Read by the log sources from their own threads, which start below.
  playback_clock_.start_mono_ns = live::monotonicNs() + std::llround(config_.sources.playback.start_delay_s * 1e9);
  for (auto& s : sources_) {
    // Named for ps, top and the tests ("src:can"); the kernel keeps 15 characters.
    s->setThreadStartHook([this, name = s->name(), driver = s->readsAtRealTimePace()] {
      pthread_setname_np(pthread_self(), ("src:" + name).substr(0, 15).c_str());
      if (driver) realtime_->applyToDriverThread(name);
    });
    s->start();
  }
  sources_started_ = true;
  spdlog::info("running: estimator at {} Hz, LCM {} (channels {}, {}, {}, {}, {}){}", config_.rate_hz, config_.lcm.url,
               config_.lcm.heading_channel, config_.lcm.attitude_channel, config_.lcm.imu_channel,
               config_.lcm.gps_channel, config_.lcm.status_channel, notifier_.underSystemd() ? ", under systemd" : "");
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
  if (publisher_ != nullptr) publisher_->stop();  // after its producer: sends what is queued
  if (nmea_out_ != nullptr) nmea_out_->stop();    // after its producer
  if (recorder_ != nullptr) recorder_->stop();    // after every producer
}

void Daemon::requestCalibrationReload() {
  if (loop_ != nullptr) loop_->requestCalibrationReload();
}

LoopSummary Daemon::summary() const { return loop_ != nullptr ? loop_->summary() : LoopSummary{}; }

}  // namespace headingd::daemon
