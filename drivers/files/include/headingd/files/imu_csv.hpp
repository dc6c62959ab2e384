#pragma once
// IMU recordings in the BROAD CSV format (tests/data/broad/README.md): header line,
// t [s], gyr_x..z [rad/s], acc_x..z [m/s²], mag_x..z [µT]; other columns ignored.
#include <string>
#include <vector>

#include "headingd/core/imu_sample.hpp"

namespace headingd::files {

// Whether the magnetometer is read. A 9-axis estimator fed a 6-axis file runs without a
// heading reference, so the header alone must not decide it: kRequired (the default) makes
// a file without all three mag_* columns (one misspelt, "mag_Z") an error; kIgnored reads no
// magnetometer whatever the header has, for a 6-axis recording or a run without the field
// (headingd-replay --no-mag, [imu_csv] no_mag = true).
enum class MagColumns { kRequired, kIgnored };

// One sample per data row, in file order (timestamps are not checked here: the estimator's
// sample gate counts gaps, duplicates and backwards steps). With MagColumns::kIgnored every
// sample has has_mag = false. Throws CsvError on malformed input.
std::vector<core::ImuSample> readImuCsv(const std::string& path, MagColumns mag = MagColumns::kRequired);

}  // namespace headingd::files
