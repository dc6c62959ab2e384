// headingd-replay: runs the estimator over a recorded IMU CSV as fast as the CPU allows and
// writes one estimate per input row.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>
#include <optional>
#include <sstream>

#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/core/imu_then_gps_order.hpp"
#include "headingd/core/mag_calibration_fit.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/core/params_toml.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/nmea_epochs.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "src/recording_replay.hpp"

namespace {

using namespace headingd;

core::EstimatorParams loadParams(const std::string& path) {
  if (path.empty()) return {};
  return core::parseEstimatorParams(files::readMaybeGzipFile(path), path);
}

// One JSON line: the row count, the estimator's counters, the time per sample.
void printCounters(const core::EstimatorCounters& c, std::size_t rows, double seconds) {
  std::fprintf(stderr, "{\"rows\":%zu", rows);
  core::forEachCounter(c, [](const char* name, std::uint64_t v) {
    std::fprintf(stderr, ",\"%s\":%llu", name, static_cast<unsigned long long>(v));
  });
  std::fprintf(stderr, ",\"estimator_ns_per_sample\":%.1f}\n", rows ? seconds * 1e9 / rows : 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Replay an IMU CSV (BROAD format, plain or gzip) through the headingd estimator."};
  std::string imu_csv, config, out;
  headingd::replay::RecordingReplayOptions recording;
  auto* imu_option =
      app.add_option("--imu-csv", imu_csv, "IMU CSV: header t,gyr_x..z [rad/s],acc_x..z [m/s^2],mag_x..z [uT]");
  auto* recording_option = app.add_option(
      "--recording", recording.dir,
      "a black-box recording folder (daemon/README.md, \"Black box\") instead of --imu-csv: replayed in the live "
      "run's order with its own configuration, calibration and World Magnetic Model (--config, --calib, --nmea and "
      "--wmm do not apply); --out gets the columns of --nmea");
  imu_option->excludes(recording_option);
  app.add_option("--lcm-log", recording.lcm_log,
                 "with --recording: also write HEADING and ATTITUDE after every IMU sample and GPS epoch to this LCM "
                 "log (utime = the sample's time), to compare with an lcm-logger log of the live run");
  app.add_option("--config", config, "TOML file with an [estimator] table (config/estimator.toml lists the keys)");
  app.add_option("--out", out, "output CSV: t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg");
  std::string nmea_path, wmm_path = HEADINGD_WMM_DEFAULT_COF;
  double nmea_first_epoch_t = 0.0;
  app.add_option("--nmea", nmea_path,
                 "NMEA capture of the GPS beside the IMU; adds the columns heading_mag_deg,declination_deg,"
                 "declination_sigma_deg,declination_source,mount_yaw_deg,heading_true_deg,mag_disturbed. "
                 "Alignment: the first NMEA epoch (first sentence with a UTC time) is at IMU time "
                 "--nmea-first-epoch-t, later epochs at that plus their UTC difference");
  app.add_option("--nmea-first-epoch-t", nmea_first_epoch_t, "IMU time [s] of the first NMEA epoch (default 0)");
  std::string calib_path;
  app.add_option("--calib", calib_path,
                 "calibration TOML (headingd-calibrate --out): gyro bias/scale, accelerometer scale/bias and "
                 "magnetometer D, offset are applied to every sample before the estimator. The magnetometer "
                 "part is set aside while it no longer fits (the calibrated field strength swings as the sensor "
                 "turns and the raw one does not, e.g. the magnet it was made for is gone) and taken back when "
                 "it fits again");
  app.add_option("--wmm", wmm_path, "World Magnetic Model coefficients (NOAA COF)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    if (!recording.dir.empty()) {
      if (out.empty() && recording.lcm_log.empty()) throw std::runtime_error("--recording needs --out or --lcm-log");
      recording.out_csv = out;
      return headingd::replay::replayRecording(recording);
    }
    if (imu_csv.empty() || out.empty()) throw std::runtime_error("--imu-csv and --out are required (or --recording)");
    const core::EstimatorParams params = loadParams(config);
    auto samples = files::readImuCsv(imu_csv);
    core::CalibratedImuStream calibration;
    if (!calib_path.empty()) {
      calibration = core::CalibratedImuStream(
          core::parseImuCalibration(files::readMaybeGzipFile(calib_path), calib_path));
      for (auto& s : samples) s = calibration.apply(s);
    }
    const bool with_gps = !nmea_path.empty();
    files::NmeaEpochs gps;
    std::optional<core::WorldMagneticModel> wmm;
    if (with_gps) {
      gps = files::readNmeaEpochs(nmea_path, nmea_first_epoch_t);
      wmm.emplace(core::parseWmmCoefficients(files::readMaybeGzipFile(wmm_path), wmm_path));
    }
    core::HeadingPipeline pipeline(params, wmm ? &*wmm : nullptr);

    // Estimates are kept in memory and written afterwards, so the timing below is the
    // estimator's alone. Each GPS epoch goes in after the first IMU sample at or after its time.
    std::vector<core::HeadingOutput> estimates(samples.size());
    core::ImuThenGpsOrder<core::GpsObservation> order;
    order.reserve(gps.epochs.size());
    for (const core::GpsObservation& epoch : gps.epochs) order.pushGps(epoch);
    const auto processGps = [&pipeline](const core::GpsObservation& epoch) { pipeline.processGps(epoch); };
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      pipeline.process(samples[i]);
      order.afterImu(samples[i].t_ns, processGps);
      estimates[i] = pipeline.output();  // a rejected sample repeats the last estimate
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::FILE* f = std::fopen(out.c_str(), "w");
    if (f == nullptr) throw std::runtime_error(out + ": cannot open for writing");
    std::fputs(with_gps ? "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg,heading_mag_deg,declination_deg,"
                          "declination_sigma_deg,declination_source,mount_yaw_deg,heading_true_deg,mag_disturbed\n"
                        : "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg\n",
               f);
    constexpr double kDeg = 180.0 / std::numbers::pi;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const auto& h = estimates[i];
      const auto& e = h.attitude;
      const double t = static_cast<double>(samples[i].t_ns) * 1e-9;
      if (!e.valid) {  // nothing usable yet: say so rather than invent an attitude
        std::fprintf(f, with_gps ? "%.9g,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,none,nan,nan,0\n"
                                 : "%.9g,nan,nan,nan,nan,nan,nan,nan\n",
                     t);
        continue;
      }
      const core::EulerAngles euler = core::eulerZyx(e.q_nb);
      std::fprintf(f, "%.9g,%.9f,%.9f,%.9f,%.9f,%.6f,%.6f,%.6f", t, e.q_nb.w(), e.q_nb.x(), e.q_nb.y(), e.q_nb.z(),
                   euler.roll_rad * kDeg, euler.pitch_rad * kDeg, euler.yaw_rad * kDeg);
      if (with_gps) {
        std::fprintf(f, ",%.6f,%.6f,%.6f,%s,%.6f,%.6f,%d", h.heading_mag_rad * kDeg, h.declination_rad * kDeg,
                     h.declination_sigma_rad * kDeg, core::declinationSourceName(h.declination_sources),
                     h.mount_yaw_rad * kDeg, h.heading_true_rad * kDeg, e.mag_disturbed ? 1 : 0);
      }
      std::fputc('\n', f);
    }
    if (std::fclose(f) != 0) throw std::runtime_error(out + ": write failed");
    printCounters(pipeline.estimator().counters(), samples.size(), seconds);
    if (!calib_path.empty()) {
      const auto& fit = calibration.magFit();
      std::fprintf(stderr, "{\"mag_calibration_set_aside\":%llu,\"mag_calibration_taken_back\":%llu,"
                   "\"mag_calibration_in_use_at_end\":%s}\n",
                   static_cast<unsigned long long>(fit.setAside()), static_cast<unsigned long long>(fit.takenBack()),
                   fit.calibrationInUse() ? "true" : "false");
    }
    if (with_gps) {
      std::fprintf(stderr, "{\"gps_epochs\":%zu,\"gps_epochs_used_for_declination\":%llu", gps.epochs.size(),
                   static_cast<unsigned long long>(pipeline.gpsEpochsUsedForDeclination()));
      nmea::forEachCounter(gps.counters, [](const char* name, std::uint64_t v) {
        std::fprintf(stderr, ",\"nmea_%s\":%llu", name, static_cast<unsigned long long>(v));
      });
      std::fputs("}\n", stderr);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-replay: %s\n", e.what());
    return 1;
  }
  return 0;
}
