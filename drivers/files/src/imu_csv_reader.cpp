#include "headingd/files/imu_csv_reader.hpp"

#include <cmath>

#include "headingd/files/numeric_csv.hpp"

namespace headingd::files {
namespace {

const std::vector<std::string> kMagColumnNames = {"mag_x", "mag_y", "mag_z"};

// "'mag_z'", and where the header has the name in another case, why it was not taken.
std::string columnAndLookAlike(const CsvRowReader& csv, const std::string& name) {
  std::string text = "'" + name + "'";
  if (const auto like = csv.headerNameLike(name)) text += " (the header has '" + *like + "': names are case-sensitive)";
  return text;
}

}  // namespace

ImuCsvReader::ImuCsvReader(const std::string& path, MagColumns mag)
    : csv_(path, {"t", "gyr_x", "gyr_y", "gyr_z", "acc_x", "acc_y", "acc_z"},
           mag == MagColumns::kRequired ? kMagColumnNames : std::vector<std::string>{}),
      has_mag_(csv_.columns().size() == 10) {
  if (mag == MagColumns::kIgnored || has_mag_) return;
  std::string missing;
  int count = 0;
  for (const auto& name : kMagColumnNames) {
    if (csv_.slot(name)) continue;
    missing += (missing.empty() ? "" : ", ") + columnAndLookAlike(csv_, name);
    ++count;
  }
  throw CsvError(path + ":1: header lacks the magnetometer's column" + (count > 1 ? "s " : " ") + missing +
                 "; a 6-axis recording is read only when declared so (headingd-replay --no-mag, [imu_csv] "
                 "no_mag = true)");
}

bool ImuCsvReader::next(core::ImuSample* sample) {
  const std::size_t columns = csv_.columns().size();  // 7, or 10 with the magnetometer
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
