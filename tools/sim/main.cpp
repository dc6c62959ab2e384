// headingd-sim: simulated IMU, GPS and ground truth for a person walking, running,
// crawling and lying, written as files a replay can read. See --help for the files, the
// time alignment of NMEA and IMU, and the scenarios. Exit codes: 0 written, 1 a file could
// not be read or written, 2 bad arguments.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "headingd/cli/parse_command_line.hpp"
#include "headingd/core/wmm.hpp"
#include "headingd/files/input_file.hpp"
#include "headingd/files/output_file.hpp"
#include "headingd/sim/output.hpp"
#include "headingd/sim/simulation.hpp"

namespace {

using namespace headingd;

constexpr int kExitFileError = 1;
constexpr int kExitBadArguments = 2;

struct BadArgument : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Strict YYYY-MM-DD (a calendar date; decimalYear rejects 2026-02-30).
void parseDate(const std::string& text, sim::SimConfig& c) {
  bool ok = text.size() == 10 && text[4] == '-' && text[7] == '-';
  for (std::size_t i = 0; ok && i < text.size(); ++i) {
    if (i != 4 && i != 7 && (text[i] < '0' || text[i] > '9')) ok = false;
  }
  if (!ok) throw BadArgument("--date: expected YYYY-MM-DD, got '" + text + "'");
  c.year = std::stoi(text.substr(0, 4));
  c.month = std::stoi(text.substr(5, 2));
  c.day = std::stoi(text.substr(8, 2));
  try {
    (void)core::decimalYear(c.year, c.month, c.day);
  } catch (const std::invalid_argument&) {
    throw BadArgument("--date: " + text + " is not a calendar date");
  }
}

std::string readFile(const std::string& path) {
  return headingd::files::readWholeFile(path, headingd::files::kWmmFileLimit);  // FileError names the file
}

// Through a temporary file renamed into place (files/output_file.hpp).
void writeFile(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  std::ostringstream text;
  write(text);
  files::writeWholeOutputFile(path.string(), text.str());
}

std::string scenarioList() {
  std::string s = "Scenarios:\n";
  for (const std::string& name : sim::scenarioNames()) {
    const sim::Scenario sc = sim::makeScenario(name);
    char head[96];
    std::snprintf(head, sizeof head, "  %s (%.0f s): ", name.c_str(), sc.durationS());
    s += head + sc.description + "\n";
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Simulated body-worn IMU and GPS with ground truth. Writes into --out-dir:\n"
      "  imu.csv    BROAD's columns "
      "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z,ref_w,ref_x,ref_y,ref_z,moving\n"
      "             (rad/s, m/s^2 specific force, uT, sensor axes). NOTE: ref_* is the TRUE attitude q_nb of the\n"
      "             SENSOR, mapping sensor axes to NED with geographic north (not BROAD's ENU/magnetic north).\n"
      "             moving = 1 while the person moves (walks, turns, gets up or down).\n"
      "  gps.nmea   NMEA 0183 GGA, RMC, VTG per epoch (CRLF, valid checksums), in time order.\n"
      "  truth.csv  per IMU row: heading_true_deg (body x-axis from geographic north), heading_mag_deg\n"
      "             (= heading_true - declination), declination_deg (WMM + --decl-anomaly-deg), lat/lon, pose, field,\n"
      "             gyro_bias_x/y/z (the gyro's true constant + drifting bias in this row, sensor axes, rad/s).\n"
      "  gps_truth.csv, sensor_errors.toml   receiver output next to the truth; the drawn IMU errors.\n"
      "Time alignment: the first IMU row is t = 0, row k is t = k/rate. GPS epoch j describes t = j/gps_rate on the\n"
      "same axis, and its sentences carry UTC = --date 12:00:00 + t. So t of an NMEA line = its UTC - (date "
      "12:00:00).\n"
      "Same arguments and seed give the same bytes."};
  sim::SimConfig c;
  std::string date = "2026-06-01", out_dir, grade = "consumer", cof = HEADINGD_SIM_DEFAULT_COF;
  app.add_option("--scenario", c.scenario, "scenario name (listed below)")->required();
  app.add_option("--seed", c.seed, "seed of all random draws (uint64)")->required();
  app.add_option("--out-dir", out_dir, "directory to write into (created if missing)")->required();
  app.add_option("--lat", c.origin.latitude_deg, "start latitude, degrees north")->capture_default_str();
  app.add_option("--lon", c.origin.longitude_deg, "start longitude, degrees east")->capture_default_str();
  app.add_option("--date", date, "UTC date of the run, YYYY-MM-DD (WMM epoch and NMEA date)")->capture_default_str();
  app.add_option("--decl-anomaly-deg", c.decl_anomaly_deg,
                 "local declination minus WMM's: the Earth field is turned east by this about down")
      ->capture_default_str();
  app.add_option("--mount-yaw-deg", c.mount_yaw_deg,
                 "IMU mounting: sensor axes = body axes turned by this about body z (down)")
      ->capture_default_str();
  app.add_option("--mount-pitch-deg", c.mount_pitch_deg,
                 "... then by this about the turned y axis (90: the sensor's x points up while the person stands)")
      ->capture_default_str();
  app.add_option("--mount-roll-deg", c.mount_roll_deg,
                 "... then by this about the turned x axis (180: the sensor's z points up, a phone screen-up)")
      ->capture_default_str();
  app.add_option("--rate-hz", c.imu_rate_hz, "IMU sample rate, 10..1000 Hz")->capture_default_str();
  app.add_option("--gps-rate-hz", c.gps_rate_hz, "GPS epochs per second: 1, 2, 4, 5 or 10")->capture_default_str();
  app.add_option("--imu-grade", grade,
                 "IMU errors: consumer (calibrated consumer MEMS, a 2014 smartphone's white noise), mems (the "
                 "same with current datasheets' white noise), uncalibrated (consumer plus Kok & Schon's raw "
                 "magnetometer distortion), phone (drawn per seed: gyro noise 0.003-0.02 rad/s per sample at 100 Hz, "
                 "constant gyro bias up to 6 deg/s, magnetometer at 25-50 Hz held between samples and 20-40 ms "
                 "late, accelerometer 0-5 ms late), ideal (none)")
      ->capture_default_str();
  std::string sampling = "interval";
  app.add_option("--vector-sampling", sampling,
                 "accelerometer and magnetometer samples: interval (the mean over the sample interval, as the "
                 "gyro's rate) or point (the value at the sample time)")
      ->capture_default_str();
  app.add_option("--accel-lag-s", c.accel_lag_s,
                 "how late the accelerometer reads against the gyro, 0..0.2 s, instead of the grade's (default: the "
                 "grade's)");
  app.add_option("--talker", c.talker, "NMEA talker id: GP or GN")->capture_default_str();
  app.add_option("--cof", cof, "WMM coefficient file (NOAA COF)")->capture_default_str();
  app.footer(scenarioList() + "Exit codes: 0 written, 1 file error, 2 bad arguments.\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;

  try {
    parseDate(date, c);
    c.imu_grade = sim::parseImuGrade(grade);
    c.vector_sampling = sim::parseVectorSampling(sampling);
    (void)sim::makeScenario(c.scenario);
    sim::validate(c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-sim: %s\nRun with --help for more information.\n", e.what());
    return kExitBadArguments;
  }

  std::optional<core::WorldMagneticModel> wmm;
  try {
    wmm.emplace(core::parseWmmCoefficients(readFile(cof), cof));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-sim: %s\n", e.what());
    return kExitFileError;
  }
  if (!wmm->isDateWithinValidity(core::decimalYear(c.year, c.month, c.day))) {
    std::fprintf(stderr, "headingd-sim: warning: %s is outside the validity of %s\n", date.c_str(),
                 wmm->modelName().c_str());
  }

  try {
    const sim::SimResult result = sim::simulate(c, *wmm);
    const std::filesystem::path dir(out_dir);
    std::filesystem::create_directories(dir);
    writeFile(dir / "imu.csv", [&](std::ostream& o) { sim::writeImuCsv(o, result); });
    writeFile(dir / "gps.nmea", [&](std::ostream& o) { sim::writeNmea(o, result); });
    writeFile(dir / "truth.csv", [&](std::ostream& o) { sim::writeTruthCsv(o, result); });
    writeFile(dir / "gps_truth.csv", [&](std::ostream& o) { sim::writeGpsTruthCsv(o, result); });
    writeFile(dir / "sensor_errors.toml", [&](std::ostream& o) { sim::writeSensorErrors(o, result); });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-sim: %s\n", e.what());
    return kExitFileError;
  }
  return 0;
}
