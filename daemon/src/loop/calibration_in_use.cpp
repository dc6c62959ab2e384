#include "headingd/daemon/loop/calibration_in_use.hpp"

#include <spdlog/spdlog.h>

#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/files/gzip_file.hpp"

namespace headingd::daemon {

core::CalibratedImuStream loadCalibration(const std::string& path) {
  if (path.empty()) return core::CalibratedImuStream{};
  return core::CalibratedImuStream(
      core::parseImuCalibration(files::readMaybeGzipFile(path, files::kConfigFileLimit), path));
}

core::ImuSample CalibrationInUse::apply(const core::ImuSample& raw) {
  const core::ImuSample calibrated = correction_.apply(raw);
  if (correction_.magFit().calibrationInUse() != mag_in_use_) logMagFitChange();
  return calibrated;
}

void CalibrationInUse::logMagFitChange() {
  mag_in_use_ = correction_.magFit().calibrationInUse();
  if (mag_in_use_) {
    spdlog::info("magnetometer calibration fits again: applied");
    return;
  }
  const core::MagCalibrationFit& fit = correction_.magFit();
  spdlog::warn(
      "magnetometer calibration no longer fits the readings (field strength raw {:.1f} uT varying "
      "{:.1f} %, calibrated {:.1f} uT varying {:.1f} %): set aside, raw magnetometer used",
      fit.rawStrength(), 100.0 * fit.rawFluctuation(), fit.calibratedStrength(), 100.0 * fit.calibratedFluctuation());
}

bool CalibrationInUse::reload() {
  if (path_.empty()) {
    spdlog::info("SIGHUP: no [daemon] calibration configured, nothing to reload");
    return false;
  }
  try {
    correction_ = loadCalibration(path_);
    mag_in_use_ = true;
    spdlog::info("SIGHUP: calibration reloaded from {}", path_);
    return true;
  } catch (const std::exception& e) {
    spdlog::error("SIGHUP: calibration not reloaded, keeping the one in use: {}", e.what());
    return false;
  }
}

}  // namespace headingd::daemon
