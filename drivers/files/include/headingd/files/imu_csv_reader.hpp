#pragma once
// IMU recordings in the BROAD CSV format (see imu_csv.hpp), one sample at a time: memory
// stays flat whatever the recording's length. Same rows, values and errors as readImuCsv.
#include <array>
#include <string>

#include "headingd/core/imu_sample.hpp"
#include "headingd/files/csv_row_reader.hpp"
#include "headingd/files/imu_csv.hpp"

namespace headingd::files {

// The largest |t| read, in seconds: int64 nanoseconds hold up to 9.22e9 s (year 2262 as UNIX
// time); the candump reader takes the same bound.
inline constexpr double kMaxImuCsvTimeS = 9e9;

class ImuCsvReader {
 public:
  // Opens the file and reads its header; throws CsvError (file, line 1, column) when a
  // required column is missing, or the mag_* columns are not there as `mag` asks (imu_csv.hpp).
  explicit ImuCsvReader(const std::string& path, MagColumns mag = MagColumns::kRequired);

  // The next sample in file order; false at the end of the file. With MagColumns::kIgnored
  // every sample has has_mag = false. Throws CsvError naming file, line and column
  // for a malformed row or a time that is not finite or beyond ±kMaxImuCsvTimeS.
  bool next(core::ImuSample* sample);
  bool hasMag() const { return has_mag_; }
  std::size_t rows() const { return csv_.rows(); }
  const std::string& path() const { return csv_.path(); }

 private:
  CsvRowReader csv_;
  bool has_mag_ = false;
  std::array<double, 10> row_{};  // t, gyr_x..z, acc_x..z, then mag_x..z if present
};

}  // namespace headingd::files
