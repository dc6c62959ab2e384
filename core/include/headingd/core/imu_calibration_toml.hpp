#pragma once
// The calibration file (TOML), read and written. Parsing and formatting only: the caller
// reads and writes the file, so core stays free of I/O.
//
//   [calibration]   method, source_file, sample_range = [first, end), created
//   [magnetometer]  D = [[..],[..],[..]] (rows), offset_uT = [x, y, z]   y_m = D m_b + o
//                   field_norm_uT, field_norm_source = "wmm" | "argument" | "data",
//                   field_norm_detail, dip_deg, noise_sigma_uT (optional)
//   [gyroscope]     bias_rad_s, scale, noise_sigma_rad_s (optional)
//   [accelerometer] bias_m_s2, scale, noise_sigma_m_s2 (optional)
//   [quality]       residual_rms_uT, coverage, condition_number (all optional)
// Absent tables keep the identity. Unknown tables or keys, wrong types and impossible
// values (a singular D, a zero scale) throw ConfigError naming file:line, the key and what
// was expected.
#include <string>
#include <string_view>

#include "headingd/core/imu_calibration.hpp"
#include "headingd/core/params_toml.hpp"  // ConfigError

namespace headingd::core {

ImuCalibration parseImuCalibration(std::string_view toml_text, const std::string& source_name);

// A document parseImuCalibration reads back to the same values (17 significant digits).
std::string formatImuCalibration(const ImuCalibration& c);

}  // namespace headingd::core
