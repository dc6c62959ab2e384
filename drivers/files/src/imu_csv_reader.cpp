#include "headingd/files/imu_csv_reader.hpp"

#include <cmath>

#include "headingd/files/numeric_csv.hpp"

namespace headingd::files {

ImuCsvReader::ImuCsvReader(const std::string& path)
    : csv_(path, {"t", "gyr_x", "gyr_y", "gyr_z", "acc_x", "acc_y", "acc_z"}, {"mag_x", "mag_y", "mag_z"}),
      has_mag_(csv_.columns().size() == 10) {}

bool ImuCsvReader::next(core::ImuSample* sample) {
  const std::size_t columns = csv_.columns().size();  // 7 to 10: a partial mag_* set is read, unused
  if (!csv_.next(std::span<double>(row_.data(), columns))) return false;
  const double t = row_[0];
  if (!std::isfinite(t)) {
    throw CsvError(path() + ":" + std::to_string(csv_.lineNumber()) + ": column 't': time must be a finite number");
  }
  // Times are int64 nanoseconds: beyond ±9.22e9 s llround overflows (every sample would then
  // look like a duplicate of the last).
  if (std::abs(t) > kMaxImuCsvTimeS) {
    throw CsvError(path() + ":" + std::to_string(csv_.lineNumber()) + ": column 't': time " + std::to_string(t) +
                   " s is beyond ±9e9 s (times are held as int64 nanoseconds)");
  }
  sample->t_ns = std::llround(t * 1e9);
  sample->gyro_rad_s = {row_[1], row_[2], row_[3]};
  sample->accel_m_s2 = {row_[4], row_[5], row_[6]};
  sample->has_mag = has_mag_;
  sample->mag_uT = has_mag_ ? core::Vec3(row_[7], row_[8], row_[9]) : core::Vec3::Zero();
  return true;
}

}  // namespace headingd::files
