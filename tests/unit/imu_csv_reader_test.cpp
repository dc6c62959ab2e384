// ImuCsvReader, the streaming IMU CSV reader, on real files: the same samples as readImuCsv,
// one at a time, from plain and gzip files larger than its buffer, with CRLF line ends, and
// errors that name file and line after the rows before them were handed out.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "headingd/files/imu_csv.hpp"
#include "headingd/files/imu_csv_reader.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "temp_csv_files.hpp"

namespace headingd::files {
namespace {

const char* kHeader = "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z,ref_w,moving\n";

// Rows i = 0..n-1 with values that tell the row and the column apart.
std::string rows(int n, const char* line_end = "\n") {
  std::string text;
  for (int i = 0; i < n; ++i) {
    const std::string k = std::to_string(i);
    text += std::to_string(i * 0.0035) + ",0." + k + ",-1." + k + ",2e-" + std::to_string(i % 9) + ",-0.236,-0.363," +
            "9.919,0.22,15.82,-38.33,0.9997,1" + line_end;
  }
  return text;
}

std::vector<core::ImuSample> readAll(ImuCsvReader& reader) {
  std::vector<core::ImuSample> samples;
  core::ImuSample s;
  while (reader.next(&s)) samples.push_back(s);
  return samples;
}

void expectSameSamples(const std::vector<core::ImuSample>& a, const std::vector<core::ImuSample>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].t_ns, b[i].t_ns) << i;
    EXPECT_EQ(a[i].gyro_rad_s, b[i].gyro_rad_s) << i;
    EXPECT_EQ(a[i].accel_m_s2, b[i].accel_m_s2) << i;
    EXPECT_EQ(a[i].mag_uT, b[i].mag_uT) << i;
    EXPECT_EQ(a[i].has_mag, b[i].has_mag) << i;
  }
}

// The message of the CsvError that reading the whole file ends with, and the samples before it.
std::string errorAfterRows(const std::string& path, std::size_t* rows_before, MagColumns mag = MagColumns::kRequired) {
  ImuCsvReader reader(path, mag);
  core::ImuSample s;
  *rows_before = 0;
  try {
    while (reader.next(&s)) ++*rows_before;
  } catch (const CsvError& e) {
    return e.what();
  }
  return "";
}

using ImuCsvReaderFiles = TempCsvFiles;

TEST_F(ImuCsvReaderFiles, RowValuesPlainAndGzipAcrossBufferRefills) {
  const std::string text = kHeader + rows(30000);  // about 2 MB: many buffer refills
  for (const std::string& path : {writePlain("big.csv", text), writeGzip("big.csv.gz", text)}) {
    ImuCsvReader reader(path);
    EXPECT_TRUE(reader.hasMag());
    const auto samples = readAll(reader);
    ASSERT_EQ(samples.size(), 30000u) << path;
    EXPECT_EQ(reader.rows(), 30000u);
    EXPECT_EQ(samples[0].t_ns, 0);
    EXPECT_EQ(samples[12345].t_ns, std::llround(std::stod(std::to_string(12345 * 0.0035)) * 1e9));
    EXPECT_EQ(samples[12345].gyro_rad_s, core::Vec3(0.12345, -1.12345, 2e-6));
    EXPECT_EQ(samples[29999].accel_m_s2, core::Vec3(-0.236, -0.363, 9.919));
    EXPECT_EQ(samples[29999].mag_uT, core::Vec3(0.22, 15.82, -38.33));
    EXPECT_FALSE(reader.next(&const_cast<core::ImuSample&>(samples[0])));  // stays at the end
  }
}

TEST_F(ImuCsvReaderFiles, SameSamplesAsReadImuCsvWithCrlfAndNoFinalNewline) {
  std::string text = std::string(kHeader) + rows(500, "\r\n");
  text.resize(text.size() - 2);  // the last row ends without a line end
  const std::string path = writePlain("crlf.csv", text);
  ImuCsvReader reader(path);
  const auto streamed = readAll(reader);
  ASSERT_EQ(streamed.size(), 500u);
  expectSameSamples(streamed, readImuCsv(path));
  const std::string lf = writePlain("lf.csv", std::string(kHeader) + rows(500));
  expectSameSamples(streamed, readImuCsv(lf));
}

TEST_F(ImuCsvReaderFiles, ALineLongerThanTheBuffer) {
  const std::string long_field(600000, 'x');  // an ignored column, longer than the read buffer
  const std::string path = writeGzip("long.csv.gz", "note,t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n" + long_field +
                                                        ",1.5,0.1,0.2,0.3,0.4,0.5,0.6\nshort,1.6,1,2,3,4,5,6\n");
  ImuCsvReader reader(path, MagColumns::kIgnored);
  EXPECT_FALSE(reader.hasMag());
  const auto samples = readAll(reader);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].t_ns, 1'500'000'000);
  EXPECT_EQ(samples[0].accel_m_s2, core::Vec3(0.4, 0.5, 0.6));
  EXPECT_EQ(samples[1].gyro_rad_s, core::Vec3(1, 2, 3));
  EXPECT_EQ(samples[1].mag_uT, core::Vec3::Zero());
}

TEST_F(ImuCsvReaderFiles, ErrorNamesFileAndLineAfterTheRowsBefore) {
  const std::string text = kHeader + rows(20000) + "70.0,0,0,0,0,oops,0,0,0,0,0,0\n" + rows(5);
  for (const std::string& path : {writePlain("bad.csv", text), writeGzip("bad.csv.gz", text)}) {
    std::size_t before = 0;
    const std::string message = errorAfterRows(path, &before);
    EXPECT_EQ(before, 20000u);
    EXPECT_NE(message.find(path + ":20002: column 'acc_y' (field 6): cannot read 'oops'"), std::string::npos)
        << message;
  }
}

TEST_F(ImuCsvReaderFiles, TruncatedLastLineAsBefore) {
  // A recording cut off mid-row: too few fields is an error naming the last line, as readImuCsv
  // always said; a row cut inside its last needed number reads what is there.
  const std::string cut_fields = writePlain("cut.csv", std::string(kHeader) + rows(3) + "0.0105,0.1,0.2");
  std::size_t before = 0;
  std::string message = errorAfterRows(cut_fields, &before);
  EXPECT_EQ(before, 3u);
  EXPECT_NE(message.find(cut_fields + ":5: 3 fields, but column 'mag_z' is field 10"), std::string::npos) << message;
  EXPECT_EQ(message, [&] {
    try {
      readImuCsv(cut_fields);
    } catch (const CsvError& e) {
      return std::string(e.what());
    }
    return std::string();
  }());

  const std::string cut_number =
      writePlain("cutnum.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,-9.81\n0.01,0,0,0,0,0,-9.");
  ImuCsvReader reader(cut_number, MagColumns::kIgnored);
  const auto samples = readAll(reader);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[1].accel_m_s2.z(), -9.0);
  expectSameSamples(samples, readImuCsv(cut_number, MagColumns::kIgnored));
}

TEST_F(ImuCsvReaderFiles, BlankLinesSkippedButCounted) {
  const std::string path =
      writePlain("blank.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,1\n\n \r\n0.01,0,0,0,0,0,x\n");
  std::size_t before = 0;
  const std::string message = errorAfterRows(path, &before, MagColumns::kIgnored);
  EXPECT_EQ(before, 1u);
  EXPECT_NE(message.find(path + ":5: column 'acc_z'"), std::string::npos) << message;
}

TEST_F(ImuCsvReaderFiles, HeaderErrorsAtOpen) {
  EXPECT_THROW(ImuCsvReader(writePlain("empty.csv", "")), CsvError);
  EXPECT_THROW(ImuCsvReader(writePlain("nocol.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_z\n")), CsvError);
  EXPECT_THROW(ImuCsvReader(writePlain("six.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n")), CsvError);
  EXPECT_NO_THROW(ImuCsvReader(writePlain("six.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n"), MagColumns::kIgnored));
  EXPECT_THROW(ImuCsvReader((dir_ / "missing.csv").string()), CsvError);
}

}  // namespace
}  // namespace headingd::files
