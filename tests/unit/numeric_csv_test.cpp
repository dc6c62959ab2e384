// The CSV readers on real files in a temporary folder, plain and gzip.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "headingd/files/gzip_file.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "temp_csv_files.hpp"

namespace headingd::files {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kImuColumns = {"t", "gyr_x", "gyr_y", "gyr_z", "acc_x", "acc_y", "acc_z"};

class CsvFiles : public TempCsvFiles {
 protected:
  // The CsvError message of reading `path` as IMU CSV, or "" if it read (most files here are
  // 6-axis, read as declared so).
  static std::string imuErrorOf(const std::string& path) {
    return messageOf<CsvError>([&] { readImuCsv(path, MagColumns::kIgnored); });
  }
};

// The message names the file, the line ("path:LINE") and the column.
void expectNamesFileLineColumn(const std::string& message, const std::string& path, int line,
                               const std::string& column) {
  ASSERT_NE(message, "") << "no CsvError for " << path;
  EXPECT_NE(message.find(path + ":" + std::to_string(line) + ":"), std::string::npos)
      << "message does not name file and line " << line << ": " << message;
  EXPECT_NE(message.find("'" + column + "'"), std::string::npos)
      << "message does not name column '" << column << "': " << message;
}

const char* kBroadLike =
    "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z,ref_w,ref_x,ref_y,ref_z,moving\n"
    "0,-0.001,-0.004,0.005,-0.236,-0.363,9.919,0.22,15.82,-38.33,0.9997,-0.0196,0.0121,-0.0013,0\n"
    "0.0035,-0.0011,0.0021,0.0074,-0.2362,-0.3298,9.8997,0.23,15.83,-38.34,0.9997,-0.0195,0.0123,-0.0014,1\n";

TEST_F(CsvFiles, ReadsABroadFilePlainAndGzip) {
  for (const std::string& path : {writePlain("plain.csv", kBroadLike), writeGzip("packed.csv.gz", kBroadLike)}) {
    const auto samples = readImuCsv(path);
    ASSERT_EQ(samples.size(), 2u) << path;
    EXPECT_EQ(samples[0].t_ns, 0);
    EXPECT_EQ(samples[1].t_ns, 3'500'000);
    EXPECT_EQ(samples[1].gyro_rad_s, core::Vec3(-0.0011, 0.0021, 0.0074));
    EXPECT_EQ(samples[1].accel_m_s2, core::Vec3(-0.2362, -0.3298, 9.8997));
    EXPECT_EQ(samples[0].mag_uT, core::Vec3(0.22, 15.82, -38.33));
    EXPECT_TRUE(samples[0].has_mag);
    EXPECT_TRUE(samples[1].has_mag);
  }
}

TEST_F(CsvFiles, GzipAndPlainGiveTheSameBytes) {
  std::string big = "a,b\n";
  for (int i = 0; i < 20000; ++i) big += std::to_string(i) + "," + std::to_string(i * 0.5) + "\n";
  EXPECT_EQ(readMaybeGzipFile(writeGzip("big.gz", big), kDbcFileLimit), big);
  EXPECT_EQ(readMaybeGzipFile(writePlain("big.csv", big), kDbcFileLimit), big);
  const NumericCsv csv = readNumericCsv(writeGzip("big2.gz", big), {"b", "a"});
  ASSERT_EQ(csv.rows, 20000u);
  EXPECT_EQ(csv.column("a")[19999], 19999.0);
  EXPECT_EQ(csv.column("b")[19999], 9999.5);
}

TEST_F(CsvFiles, ColumnsInAnyOrderAndExtraColumnsIgnored) {
  const std::string path = writePlain("shuffled.csv",
                                      "note,acc_z,t,gyr_z,acc_x,extra,gyr_x,acc_y,gyr_y\n"
                                      "hello,-9.81,1.5,0.3,0.1,not a number,0.1,0.2,0.2\n"
                                      "world,-9.80,1.51,0.6,0.4,,0.4,0.5,0.5\n");
  const auto samples = readImuCsv(path, MagColumns::kIgnored);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].t_ns, 1'500'000'000);
  EXPECT_EQ(samples[1].t_ns, 1'510'000'000);
  EXPECT_EQ(samples[0].gyro_rad_s, core::Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(samples[0].accel_m_s2, core::Vec3(0.1, 0.2, -9.81));
  EXPECT_EQ(samples[1].gyro_rad_s, core::Vec3(0.4, 0.5, 0.6));
  EXPECT_EQ(samples[1].accel_m_s2, core::Vec3(0.4, 0.5, -9.80));
}

TEST_F(CsvFiles, AFileWithoutTheMagnetometerIsRefusedUnlessDeclaredSixAxis) {
  const std::string path = writePlain("nomag.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,-9.81\n");
  const std::string m = messageOf<CsvError>([&] { readImuCsv(path); });
  EXPECT_NE(
      m.find(path + ":1: header lacks the magnetometer's columns 'mag_x', 'mag_y', 'mag_z'; a 6-axis "
                    "recording is read only when declared so (headingd-replay --no-mag, [imu_csv] no_mag = true)"),
      std::string::npos)
      << m;
  const auto samples = readImuCsv(path, MagColumns::kIgnored);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_FALSE(samples[0].has_mag);
  EXPECT_EQ(samples[0].accel_m_s2, core::Vec3(0, 0, -9.81));
}

TEST_F(CsvFiles, OneMisspeltMagnetometerColumnIsNamedNotDroppedSilently) {
  // The hidden run's file: mag_Z for mag_z was replayed without the magnetometer, exit 0.
  const std::string path =
      writePlain("mag_Z.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_Z\n0,0,0,0,0,0,-9.81,1,2,3\n");
  const std::string m = messageOf<CsvError>([&] { readImuCsv(path); });
  EXPECT_NE(m.find(path + ":1: header lacks the magnetometer's column 'mag_z' (the header has 'mag_Z': names are "
                          "case-sensitive)"),
            std::string::npos)
      << m;
  // Two of the three are refused alike; declared 6-axis, the columns that are there are not read.
  const std::string partial =
      writePlain("partial.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y\n0,0,0,0,0,0,-9.81,1,2\n");
  EXPECT_NE(messageOf<CsvError>([&] { readImuCsv(partial); }).find("lacks the magnetometer's column 'mag_z'"),
            std::string::npos);
  EXPECT_FALSE(readImuCsv(partial, MagColumns::kIgnored)[0].has_mag);
  // A required column in another case is named the same way.
  const std::string upper = writePlain("upper.csv", "t,gyr_x,gyr_y,gyr_z,ACC_X,acc_y,acc_z\n0,0,0,0,0,0,-9.81\n");
  EXPECT_NE(imuErrorOf(upper).find(":1: header has no column 'acc_x' (it has 'ACC_X': names are case-sensitive)"),
            std::string::npos)
      << imuErrorOf(upper);
}

TEST_F(CsvFiles, AColumnNamedTwiceIsRefusedNotTheFirstTaken) {
  const std::string path =
      writePlain("twice.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z,t\n0,0,0,0,0,0,-9.81,1,2,3,5\n");
  const std::string m = messageOf<CsvError>([&] { readImuCsv(path); });
  EXPECT_NE(m.find(path + ":1: column 't' is named twice in the header (fields 1 and 11)"), std::string::npos) << m;
}

TEST_F(CsvFiles, DeclaredSixAxisIgnoresMagnetometerColumnsThatAreThere) {
  const std::string path =
      writePlain("nine.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n0,0,0,0,0,0,-9.81,1,2,3\n");
  EXPECT_TRUE(readImuCsv(path)[0].has_mag);
  EXPECT_FALSE(readImuCsv(path, MagColumns::kIgnored)[0].has_mag);
}

TEST_F(CsvFiles, NanAndOtherNumberFormsAreValues) {
  const std::string path = writePlain("forms.csv",
                                      "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\r\n"
                                      "0.01,nan,NaN,inf,+1.5, 2e-3 ,-9.81,-inf,1E2,0\r\n");
  const auto samples = readImuCsv(path);
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_TRUE(std::isnan(samples[0].gyro_rad_s.x()));
  EXPECT_TRUE(std::isnan(samples[0].gyro_rad_s.y()));
  EXPECT_EQ(samples[0].gyro_rad_s.z(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(samples[0].accel_m_s2, core::Vec3(1.5, 2e-3, -9.81));
  EXPECT_EQ(samples[0].mag_uT.x(), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(samples[0].mag_uT.y(), 100.0);
  EXPECT_EQ(samples[0].t_ns, 10'000'000);
}

TEST_F(CsvFiles, HeaderOnlyAndTrailingBlankLines) {
  const NumericCsv empty = readNumericCsv(writePlain("header.csv", "a,b\n"), {"a"}, {"b", "c"});
  EXPECT_EQ(empty.rows, 0u);
  EXPECT_TRUE(empty.has("a"));
  EXPECT_TRUE(empty.has("b"));
  EXPECT_FALSE(empty.has("c"));
  EXPECT_EQ(empty.header, (std::vector<std::string>{"a", "b"}));
  const NumericCsv trailing = readNumericCsv(writePlain("trailing.csv", "a\n1\n2\n\n\n"), {"a"});
  EXPECT_EQ(trailing.rows, 2u);
  EXPECT_EQ(trailing.column("a"), (std::vector<double>{1.0, 2.0}));
}

TEST_F(CsvFiles, NonNumericValueNamesFileLineAndColumn) {
  const std::string text = std::string(kBroadLike) + "0.007,0,0,0,0,0,oops,1,2,3,1,0,0,0,0\n";
  for (const std::string& path : {writePlain("bad.csv", text), writeGzip("bad.csv.gz", text)}) {
    const std::string m = imuErrorOf(path);
    expectNamesFileLineColumn(m, path, 4, "acc_z");
    EXPECT_NE(m.find("oops"), std::string::npos) << m;
  }
}

TEST_F(CsvFiles, EmptyFieldIsAnError) {
  const std::string path = writePlain("emptyfield.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,,0,0,0,-9.81\n");
  expectNamesFileLineColumn(imuErrorOf(path), path, 2, "gyr_y");
}

TEST_F(CsvFiles, TooFewFieldsNamesFileLineAndColumn) {
  const std::string path = writePlain("short.csv",
                                      "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n"
                                      "0,0,0,0,0,0,-9.81\n"
                                      "0.01,0,0,0,0\n");
  expectNamesFileLineColumn(imuErrorOf(path), path, 3, "acc_z");
}

TEST_F(CsvFiles, MissingRequiredColumnNamesFileLineAndColumn) {
  const std::string path = writePlain("nocol.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_z\n0,0,0,0,0,-9.81\n");
  expectNamesFileLineColumn(imuErrorOf(path), path, 1, "acc_y");
  // Headerless data: the first line is taken as the header and the columns are missing.
  const std::string headerless = writePlain("headerless.csv", "0,0,0,0,0,0,-9.81\n");
  expectNamesFileLineColumn(imuErrorOf(headerless), headerless, 1, "t");
}

TEST_F(CsvFiles, NonFiniteTimeIsAnError) {
  const std::string path =
      writePlain("nant.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,-9.81\nnan,0,0,0,0,0,-9.81\n");
  expectNamesFileLineColumn(imuErrorOf(path), path, 3, "t");
}

TEST_F(CsvFiles, EmptyFileIsAnError) {
  for (const std::string& path : {writePlain("empty.csv", ""), writeGzip("empty.csv.gz", "")}) {
    const std::string m = imuErrorOf(path);
    ASSERT_NE(m, "") << path;
    EXPECT_NE(m.find(path), std::string::npos) << m;
    EXPECT_NE(m.find("empty"), std::string::npos) << m;
    EXPECT_THROW(readNumericCsv(path, {"a"}), CsvError);
  }
}

TEST_F(CsvFiles, MissingFileIsAnError) {
  const std::string path = (dir_ / "does-not-exist.csv").string();
  const std::string m = imuErrorOf(path);
  ASSERT_NE(m, "");
  EXPECT_NE(m.find(path), std::string::npos) << m;
  EXPECT_NE(m.find("cannot open"), std::string::npos) << m;
  EXPECT_THROW(readMaybeGzipFile(path, kConfigFileLimit), FileError);  // a file, not a CSV, failed
}

TEST_F(CsvFiles, ReadNumericCsvOptionalColumns) {
  const std::string path = writePlain("opt.csv", "x,y\n1,2\n3,4\n");
  const NumericCsv csv = readNumericCsv(path, {"y"}, {"x", "z"});
  EXPECT_EQ(csv.path, path);
  EXPECT_EQ(csv.rows, 2u);
  EXPECT_EQ(csv.column("x"), (std::vector<double>{1.0, 3.0}));
  EXPECT_EQ(csv.column("y"), (std::vector<double>{2.0, 4.0}));
  EXPECT_FALSE(csv.has("z"));
  // A required column that is missing throws, an optional one does not.
  EXPECT_THROW(readNumericCsv(path, {"z"}), CsvError);
}

}  // namespace
}  // namespace headingd::files
