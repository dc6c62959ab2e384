#pragma once
// IMU recordings in the BROAD CSV format (tests/data/broad/README.md): header line,
// t [s], gyr_x..z [rad/s], acc_x..z [m/s²], mag_x..z [µT]; other columns ignored.
#include <string>
#include <vector>

#include "headingd/core/imu_sample.hpp"

namespace headingd::files {

// One sample per data row, in file order (timestamps are not checked here: the estimator's
// sample gate counts gaps, duplicates and backwards steps). Without mag_* columns every
// sample has has_mag = false. Throws CsvError on malformed input.
std::vector<core::ImuSample> readImuCsv(const std::string& path);

}  // namespace headingd::files
