#include "headingd/files/imu_csv.hpp"

#include <cmath>

#include "headingd/files/numeric_csv.hpp"

namespace headingd::files {

std::vector<core::ImuSample> readImuCsv(const std::string& path) {
  const NumericCsv csv =
      readNumericCsv(path, {"t", "gyr_x", "gyr_y", "gyr_z", "acc_x", "acc_y", "acc_z"}, {"mag_x", "mag_y", "mag_z"});
  const bool has_mag = csv.has("mag_x") && csv.has("mag_y") && csv.has("mag_z");
  const auto& t = csv.column("t");
  auto col = [&](const char* name) { return csv.column(name).data(); };
  const double *gx = col("gyr_x"), *gy = col("gyr_y"), *gz = col("gyr_z");
  const double *ax = col("acc_x"), *ay = col("acc_y"), *az = col("acc_z");
  const double *mx = has_mag ? col("mag_x") : nullptr, *my = has_mag ? col("mag_y") : nullptr,
               *mz = has_mag ? col("mag_z") : nullptr;

  std::vector<core::ImuSample> samples(csv.rows);
  for (std::size_t i = 0; i < csv.rows; ++i) {
    if (!std::isfinite(t[i])) {
      throw CsvError(path + ":" + std::to_string(i + 2) + ": column 't': time must be a finite number");
    }
    auto& s = samples[i];
    s.t_ns = std::llround(t[i] * 1e9);
    s.gyro_rad_s = {gx[i], gy[i], gz[i]};
    s.accel_m_s2 = {ax[i], ay[i], az[i]};
    s.has_mag = has_mag;
    if (has_mag) s.mag_uT = {mx[i], my[i], mz[i]};
  }
  return samples;
}

}  // namespace headingd::files
