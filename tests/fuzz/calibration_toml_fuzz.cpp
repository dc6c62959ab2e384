// The calibration file (TOML): parseImuCalibration on arbitrary text, as the daemon (at
// start-up and on SIGHUP), headingd-replay and headingd-calibrate read it. Invariants: only
// ConfigError is thrown; a calibration that parsed can be applied (ImuCorrection accepts it)
// and written back (formatImuCalibration) to a document that parses to the same text again.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "headingd/core/imu_calibration.hpp"
#include "headingd/core/imu_calibration_toml.hpp"

using namespace headingd;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  core::ImuCalibration calibration;
  try {
    calibration = core::parseImuCalibration(text, "fuzz.toml");
  } catch (const core::ConfigError&) {
    return 0;
  }
  const core::ImuCorrection correction(calibration);
  core::ImuSample sample;
  sample.gyro_rad_s = core::Vec3(0.1, -0.2, 0.3);
  sample.accel_m_s2 = core::Vec3(0.0, 0.0, 9.81);
  sample.mag_uT = core::Vec3(20.0, 0.0, 40.0);
  (void)correction.apply(sample);

  const std::string written = core::formatImuCalibration(calibration);
  core::ImuCalibration again;
  try {
    again = core::parseImuCalibration(written, "written.toml");
  } catch (const core::ConfigError& e) {
    std::fprintf(stderr, "%s\n--- written:\n%s\n", e.what(), written.c_str());
    FUZZ_CHECK(!"a written calibration reads back");
  }
  FUZZ_CHECK(core::formatImuCalibration(again) == written);
  return 0;
}
