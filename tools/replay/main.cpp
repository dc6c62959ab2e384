// headingd-replay: runs the estimator over a recorded IMU CSV as fast as the CPU allows and
// writes one estimate per input row. Reads, estimates and writes row by row
// (headingd/replay/replay_loop.hpp), so memory stays flat whatever the input's length.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>

#include "headingd/cli/parse_command_line.hpp"
#include "headingd/core/calibrated_imu_stream.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/core/params_toml.hpp"
#include "headingd/core/two_filter_smoother.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/imu_csv_reader.hpp"
#include "headingd/files/nmea_epochs.hpp"
#include "headingd/files/output_file.hpp"
#include "headingd/replay/replay_csv_writer.hpp"
#include "headingd/replay/replay_loop.hpp"
#include "headingd/replay/replay_report.hpp"
#include "headingd/replay/smooth_replay.hpp"
#include "src/recording_replay.hpp"
#include "src/replay_place.hpp"

namespace {

using namespace headingd;

core::EstimatorParams loadParams(const std::string& path) {
  if (path.empty()) return {};
  return core::parseEstimatorParams(files::readMaybeGzipFile(path, files::kConfigFileLimit), path);
}

// Each output against every input, the other output and, with --recording, every file of the
// recording folder.
void refuseOverwritingInputs(const std::vector<files::NamedPath>& outputs, std::vector<files::NamedPath> inputs,
                             const std::string& recording_dir) {
  if (!recording_dir.empty()) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(recording_dir, ec)) {
      inputs.emplace_back("--recording", entry.path().string());
    }
  }
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    std::vector<files::NamedPath> others = inputs;
    for (std::size_t j = 0; j < i; ++j) others.push_back(outputs[j]);
    if (!outputs[i].second.empty()) files::refuseOutputOverInputs(outputs[i], others);
  }
}

// --place LAT,LON[,HEIGHT_M] and --place-date YYYY-MM-DD; throws std::invalid_argument
// naming the option.
core::ConfiguredPlace placeOption(const std::vector<double>& values, const std::string& date) {
  core::ConfiguredPlace place;
  place.position.latitude_deg = values.at(0);
  place.position.longitude_deg = values.at(1);
  place.position.height_km = values.size() > 2 ? 1e-3 * values[2] : 0.0;
  if (!(std::abs(place.position.latitude_deg) <= 90.0) || !(std::abs(place.position.longitude_deg) <= 180.0) ||
      !(place.position.height_km >= -1.0 && place.position.height_km <= 850.0)) {
    throw std::invalid_argument(
        "--place: expected LAT in [-90, 90], LON in [-180, 180] degrees and HEIGHT_M in "
        "[-1000, 850000] m");
  }
  if (!date.empty()) {
    int y = 0, m = 0, d = 0;
    char tail = 0;
    if (std::sscanf(date.c_str(), "%4d-%2d-%2d%c", &y, &m, &d, &tail) != 3) {
      throw std::invalid_argument("--place-date: '" + date + "': expected YYYY-MM-DD");
    }
    try {
      place.decimal_year = core::decimalYear(y, m, d);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--place-date: '" + date + "': " + e.what());
    }
  }
  return place;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Replay an IMU CSV (BROAD format, plain or gzip) through the headingd estimator, row by row. "
      "On stderr: a JSON line with the row count, the estimator's counters and estimator_ns_per_sample "
      "(time in the estimator alone, reading and writing not in it: measured on every 16th row and on "
      "every GPS epoch). A malformed "
      "row stops the replay with exit status 1, and nothing is written: every output is written to a temporary "
      "file in the same folder and renamed into place only when complete. An output that is the same file as an "
      "input (also through a link) is refused."};
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
  app.add_option("--out", out,
                 "output CSV: t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg,heading_sigma_deg (the 1-sigma of yaw_deg; "
                 "103.9 until the first field sample)");
  std::string nmea_path, wmm_path = HEADINGD_WMM_DEFAULT_COF;
  double nmea_first_epoch_t = 0.0;
  app.add_option(
      "--nmea", nmea_path,
      "NMEA capture of the GPS beside the IMU; adds the columns heading_mag_deg,declination_deg,"
      "declination_sigma_deg,declination_source,mount_yaw_deg,heading_true_deg,mag_disturbed,heading_mag_sigma_deg,"
      "heading_true_sigma_deg (in place of heading_sigma_deg; inf while no declination is known). "
      "Alignment: the first NMEA epoch (first sentence with a UTC time) is at IMU time "
      "--nmea-first-epoch-t, later epochs at that plus their UTC difference");
  app.add_option("--nmea-first-epoch-t", nmea_first_epoch_t, "IMU time [s] of the first NMEA epoch (default 0)")
      ->check(CLI::Range(-9e9, 9e9));
  std::string calib_path;
  app.add_option("--calib", calib_path,
                 "calibration TOML (headingd-calibrate --out): gyro bias/scale, accelerometer scale/bias and "
                 "magnetometer D, offset are applied to every sample before the estimator. The magnetometer "
                 "part is set aside while it no longer fits (the calibrated field strength swings as the sensor "
                 "turns and the raw one does not, e.g. the magnet it was made for is gone) and taken back when "
                 "it fits again");
  app.add_option("--wmm", wmm_path, "World Magnetic Model coefficients (NOAA COF)")->capture_default_str();
  std::vector<double> place_values;
  std::string place_date;
  auto* place_option =
      app.add_option("--place", place_values,
                     "LAT,LON[,HEIGHT_M]: where the recording was made (degrees, metres above the WGS-84 ellipsoid), "
                     "as the daemon's [place]: the World Magnetic Model there gives the reference field and the "
                     "declination until a GPS fix (--nmea) gives a position; adds the true-heading columns of --nmea")
          ->delimiter(',')
          ->expected(2, 3);
  app.add_option("--place-date", place_date, "YYYY-MM-DD: the date for --place (default: today, as the daemon)")
      ->needs(place_option);
  place_option->excludes(recording_option);
  bool no_mag = false;
  auto* no_mag_option =
      app.add_flag("--no-mag", no_mag,
                   "read no magnetometer: a 6-axis recording (without it, a file lacking one of mag_x, mag_y, mag_z is "
                   "refused), or a run without the field; the heading then runs on the gyro alone");
  bool smooth = false;
  auto* smooth_option = app.add_flag(
      "--smooth", smooth,
      "offline smoothing: the estimator forward and over the samples reversed in time, each sample's two attitudes "
      "fused by their covariances (core/two_filter_smoother.hpp): tilt and heading smoothed, heading_sigma_deg "
      "the smaller of the two filters'; the same columns. Reads the whole CSV into memory (about 220 "
      "bytes per sample: 78 MB per hour at 100 Hz); not with --nmea or --recording. The counters are the forward "
      "filter's");
  smooth_option->excludes(recording_option);
  no_mag_option->excludes(recording_option);
  app.footer(
      std::string(
          "Exit codes: 0 replayed and written, 1 an input cannot be read or is malformed, or an output cannot be "
          "written (the message names the file), 2 bad arguments (also an output that is an input).") +
      "\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;

  std::optional<core::ConfiguredPlace> place;
  try {
    if (!place_values.empty()) place = placeOption(place_values, place_date);
    if (!recording.dir.empty() && out.empty() && recording.lcm_log.empty()) {
      throw std::runtime_error("--recording needs --out or --lcm-log");
    }
    if (recording.dir.empty() && (imu_csv.empty() || out.empty())) {
      throw std::runtime_error("--imu-csv and --out are required (or --recording)");
    }
    if (smooth && !nmea_path.empty()) {
      throw std::runtime_error("--smooth smooths the attitude alone: it does not take --nmea (true heading)");
    }
    refuseOverwritingInputs({{"--out", out}, {"--lcm-log", recording.lcm_log}},
                            {{"--imu-csv", imu_csv},
                             {"--config", config},
                             {"--nmea", nmea_path},
                             {"--calib", calib_path},
                             {"--wmm", wmm_path}},
                            recording.dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-replay: %s\n", e.what());
    return headingd::cli::kExitBadArguments;
  }

  try {
    if (!recording.dir.empty()) {
      recording.out_csv = out;
      return headingd::replay::replayRecording(recording);
    }
    const core::EstimatorParams params = loadParams(config);
    files::ImuCsvReader imu(imu_csv, no_mag ? files::MagColumns::kIgnored : files::MagColumns::kRequired);
    const bool calibrated = !calib_path.empty();
    core::CalibratedImuStream calibration;
    if (calibrated) {
      calibration = core::CalibratedImuStream(
          core::parseImuCalibration(files::readMaybeGzipFile(calib_path, files::kConfigFileLimit), calib_path));
    }
    const bool with_gps = !nmea_path.empty();
    files::NmeaEpochs gps;  // 1 Hz: small enough to read whole
    std::optional<core::WorldMagneticModel> wmm;
    if (with_gps) {
      gps = files::readNmeaEpochs(nmea_path, nmea_first_epoch_t);
      wmm.emplace(core::parseWmmCoefficients(files::readMaybeGzipFile(wmm_path, files::kWmmFileLimit), wmm_path));
    }
    if (place && !wmm) {
      wmm.emplace(core::parseWmmCoefficients(files::readMaybeGzipFile(wmm_path, files::kWmmFileLimit), wmm_path));
    }
    core::HeadingPipeline pipeline(params, wmm ? &*wmm : nullptr);
    if (place) replay::usePlace(pipeline, *place, *wmm);
    replay::GpsOrder order;
    order.reserve(gps.epochs.size());
    for (const core::GpsObservation& epoch : gps.epochs) order.pushGps(epoch);

    replay::ReplayCsvWriter writer(out, with_gps || place.has_value());
    const auto nextSample = [&](core::ImuSample* sample) {
      if (!imu.next(sample)) return false;
      if (calibrated) *sample = calibration.apply(*sample);
      return true;
    };
    if (smooth) {
      // The pipeline before any sample: with --place, its reference field and declination.
      const replay::SmoothedReplay smoothed = replay::smoothSamples(nextSample, pipeline, writer);
      writer.close();
      replay::printCounters(smoothed.forward_counters, smoothed.totals);
      if (calibrated) replay::printMagCalibration(calibration.magFit());
      return 0;
    }
    const replay::ReplayTotals totals = replay::replaySamples(nextSample, pipeline, order, writer);
    writer.close();

    replay::printCounters(pipeline.estimator().counters(), totals);
    if (calibrated) replay::printMagCalibration(calibration.magFit());
    if (with_gps) replay::printGps(gps, pipeline);
    replay::printSensorUnits(pipeline);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-replay: %s\n", e.what());
    return 1;
  }
  return 0;
}
