#include "recording_replay.hpp"

#include <toml++/toml.h>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>

#include "headingd/core/calibrated_imu_stream.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/core/toml_document.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/daemon/outputs/lcm_messages.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/lcm_export/lcm_log_writer.hpp"
#include "headingd/recording/recording_format.hpp"
#include "headingd/recording/recording_reader.hpp"
#include "headingd/replay/replay_csv_writer.hpp"
#include "headingd/replay/replay_report.hpp"
#include "replay_place.hpp"

namespace headingd::replay {
namespace {

// The channels the live run published on (its [lcm] table), so that the log written here
// lines up with an lcm-logger log of the live run.
struct Channels {
  std::string heading = "HEADING", attitude = "ATTITUDE";
};

Channels channelsOf(const std::string& folder) {
  Channels c;
  const std::string path = folder + "/" + std::string(recording::kConfigFile);
  const toml::table doc = core::parseTomlDocument(files::readMaybeGzipFile(path, files::kConfigFileLimit), path);
  if (const auto* heading = doc["lcm"]["heading_channel"].as_string()) c.heading = heading->get();
  if (const auto* attitude = doc["lcm"]["attitude_channel"].as_string()) c.attitude = attitude->get();
  return c;
}

// HEADING and ATTITUDE as the daemon fills them, into an LCM log. Their utime is the sample's
// time (there is no publish time offline), their validity FRESH once there is an estimate.
class EstimateLog {
 public:
  EstimateLog(const std::string& path, Channels channels) : log_(path), channels_(std::move(channels)) {}
  void write(const core::HeadingPipeline& pipeline, std::int64_t sample_t_ns) {
    const core::HeadingOutput& out = pipeline.output();
    daemon::PublishTimes t;
    t.sample_utime_us = sample_t_ns / 1000;
    t.utime_us = t.sample_utime_us;
    const daemon::Validity v = out.attitude.valid ? daemon::Validity::kFresh : daemon::Validity::kNone;
    daemon::fillHeading(heading_, out, v, t);
    daemon::fillAttitude(attitude_, out, pipeline.estimator().ekf().covariance(), v, t);
    log_.write(channels_.heading, t.utime_us, heading_);
    log_.write(channels_.attitude, t.utime_us, attitude_);
  }
  void close() { log_.close(); }

 private:
  lcm_export::LcmLogWriter log_;
  Channels channels_;
  headingd::heading_t heading_{};
  headingd::attitude_t attitude_{};
};

void printRecordingCounters(const recording::RecordingReader& reader, const core::HeadingPipeline& pipeline) {
  const recording::RecordingCounters& c = reader.counters();
  std::fprintf(
      stderr,
      "{\"recording_complete\":%s,\"can_frames\":%llu,\"can_flushes\":%llu,\"imu_samples\":%llu,"
      "\"imu_dropped_live\":%llu,\"gps_epochs\":%llu,\"gps_epochs_not_placed\":%llu,\"gps_values_ignored\":%llu,"
      "\"gps_dates_not_believed\":%llu,"
      "\"calibration_reloads\":%llu,\"lost_lines\":%llu,\"bad_lines\":%llu,\"start_missing\":%s}\n",
      reader.complete() ? "true" : "false", static_cast<unsigned long long>(c.can_frames),
      static_cast<unsigned long long>(c.can_flushes), static_cast<unsigned long long>(c.imu_samples),
      static_cast<unsigned long long>(c.imu_dropped_live), static_cast<unsigned long long>(c.gps_epochs),
      static_cast<unsigned long long>(c.gps_epochs_not_placed),
      static_cast<unsigned long long>(pipeline.gpsValuesIgnored()),
      static_cast<unsigned long long>(pipeline.gpsDatesNotBelieved()),
      static_cast<unsigned long long>(c.calibration_reloads), static_cast<unsigned long long>(c.lost_lines),
      static_cast<unsigned long long>(c.bad_lines), c.start_missing ? "true" : "false");
  if (!c.first_bad_line.empty())
    std::fprintf(stderr, "headingd-replay: first unreadable line: %s\n", c.first_bad_line.c_str());
}

}  // namespace

int replayRecording(const RecordingReplayOptions& options) {
  const recording::RecordingSetup setup = recording::loadRecordingSetup(options.dir);
  std::optional<core::WorldMagneticModel> wmm;
  if (!setup.wmm_path.empty()) {
    wmm.emplace(
        core::parseWmmCoefficients(files::readMaybeGzipFile(setup.wmm_path, files::kWmmFileLimit), setup.wmm_path));
  }
  core::CalibratedImuStream calibration;
  if (!setup.calibration_path.empty()) {
    calibration = core::CalibratedImuStream(core::parseImuCalibration(
        files::readMaybeGzipFile(setup.calibration_path, files::kConfigFileLimit), setup.calibration_path));
  }
  core::HeadingPipeline pipeline(setup.estimator, wmm ? &*wmm : nullptr);
  if (setup.place && wmm) usePlace(pipeline, *setup.place, *wmm);
  if (setup.gps_date_seed) pipeline.seedGpsDate(*setup.gps_date_seed);
  recording::RecordingReader reader(setup);

  std::unique_ptr<ReplayCsvWriter> rows;
  if (!options.out_csv.empty()) rows = std::make_unique<ReplayCsvWriter>(options.out_csv, /*with_gps=*/true);
  std::unique_ptr<EstimateLog> estimates;
  if (!options.lcm_log.empty()) estimates = std::make_unique<EstimateLog>(options.lcm_log, channelsOf(setup.folder));

  // The row of an IMU sample is written once the GPS epochs that went in after it are in too,
  // as the live loop publishes after both.
  std::optional<std::int64_t> row_pending_t_ns;
  std::int64_t last_used_t_ns = 0;
  std::size_t samples = 0;
  recording::RecordingStep step;
  const auto start = std::chrono::steady_clock::now();
  while (reader.next(step)) {
    switch (step.kind) {
      case recording::RecordingStep::Kind::kImu: {
        if (rows && row_pending_t_ns) rows->write(*row_pending_t_ns, pipeline.output());
        const core::SampleVerdict verdict = pipeline.process(calibration.apply(step.imu));
        if (core::sampleUsed(verdict)) last_used_t_ns = step.imu.t_ns;
        row_pending_t_ns = step.imu.t_ns;
        ++samples;
        break;
      }
      case recording::RecordingStep::Kind::kGps: pipeline.processGps(step.gps); break;
      case recording::RecordingStep::Kind::kCalibrationReloaded:
        std::fprintf(stderr,
                     "headingd-replay: the live run re-read its calibration after %zu IMU samples (SIGHUP); "
                     "this replay keeps the one recorded at the start\n",
                     samples);
        continue;
    }
    if (estimates) estimates->write(pipeline, last_used_t_ns);
  }
  if (rows && row_pending_t_ns) rows->write(*row_pending_t_ns, pipeline.output());
  // Here the time is the whole loop's, reading and writing included.
  const ReplayTotals totals{
      samples, std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)};
  if (rows) rows->close();
  if (estimates) estimates->close();
  printCounters(pipeline.estimator().counters(), totals);
  printRecordingCounters(reader, pipeline);
  printSensorUnits(pipeline);
  return 0;
}

}  // namespace headingd::replay
