#include "headingd/files/imu_csv.hpp"

#include "headingd/files/imu_csv_reader.hpp"

namespace headingd::files {

std::vector<core::ImuSample> readImuCsv(const std::string& path, MagColumns mag) {
  ImuCsvReader reader(path, mag);
  std::vector<core::ImuSample> samples;
  core::ImuSample sample;
  while (reader.next(&sample)) samples.push_back(sample);
  return samples;
}

}  // namespace headingd::files
