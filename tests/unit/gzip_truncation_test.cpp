// gzip files cut short or corrupt, through every reader of drivers/files: a cut stream is
// never read as a whole file (the readers throw, naming the file; readMaybeGzipLog keeps what
// was read and says the end is missing), a failed CRC or length check is a corrupt file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "headingd/files/gzip_file.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/imu_csv_reader.hpp"
#include "headingd/files/input_file.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "temp_csv_files.hpp"

namespace headingd::files {
namespace {

// An IMU CSV of `rows` rows with noisy values (so the gzip stream is long enough to cut).
std::string noisyImuCsv(int rows) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  std::string text = "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n";
  for (int i = 0; i < rows; ++i) {
    text += std::to_string(i * 0.01);
    for (int c = 0; c < 9; ++c) text += "," + std::to_string(noise(rng));
    text += "\n";
  }
  return text;
}

class GzipFiles : public TempCsvFiles {
 protected:
  // A copy of `path` with only its first `bytes` bytes (or all but the last `-bytes`).
  std::string cutCopy(const std::string& path, const std::string& name, long bytes) {
    std::ifstream in(path, std::ios::binary);
    std::string data{std::istreambuf_iterator<char>(in), {}};
    data.resize(static_cast<std::size_t>(bytes >= 0 ? bytes : static_cast<long>(data.size()) + bytes));
    return writePlain(name, data);
  }
  // A copy of `path` with byte `at` (from the end if negative) inverted.
  std::string flippedCopy(const std::string& path, const std::string& name, long at) {
    std::ifstream in(path, std::ios::binary);
    std::string data{std::istreambuf_iterator<char>(in), {}};
    const auto i = static_cast<std::size_t>(at >= 0 ? at : static_cast<long>(data.size()) + at);
    data[i] = static_cast<char>(~data[i]);
    return writePlain(name, data);
  }
  // The message of what a reader throws: CsvError from the CSV readers, FileError from the
  // whole-file reads (gzip_file.hpp).
  static std::string errorOf(auto read) { return messageOf<std::runtime_error>(read); }
};

TEST_F(GzipFiles, ACutStreamIsAnErrorNamingTheFileForEveryReader) {
  const std::string text = noisyImuCsv(20000);
  const std::string whole = writeGzip("imu.csv.gz", text);
  const auto size = static_cast<long>(std::filesystem::file_size(whole));
  // Cut in the compressed data, in the 8-byte trailer (CRC-32, length), and in the header.
  for (const long bytes : {size / 3, size - 1, size - 8, 10L}) {
    const std::string cut = cutCopy(whole, "cut-" + std::to_string(bytes) + ".csv.gz", bytes);
    for (const std::string& m :
         {errorOf([&] { readImuCsv(cut); }), errorOf([&] { readMaybeGzipFile(cut, kWholeLogLimit); }),
          errorOf([&] { readNumericCsv(cut, {"t"}); })}) {
      EXPECT_NE(m.find(cut + ": truncated gzip file"), std::string::npos) << bytes << ": " << m;
    }
  }
}

TEST_F(GzipFiles, TheStreamingReaderHandsOutTheRowsBeforeItThrows) {
  const std::string text = noisyImuCsv(20000);
  const std::string whole = writeGzip("imu.csv.gz", text);
  const std::string cut = cutCopy(whole, "cut.csv.gz", static_cast<long>(std::filesystem::file_size(whole)) / 2);
  ImuCsvReader reader(cut);
  core::ImuSample sample;
  std::size_t rows = 0;
  const std::string m = errorOf([&] {
    while (reader.next(&sample)) ++rows;
  });
  EXPECT_GT(rows, 1000u);
  EXPECT_LT(rows, 20000u);
  EXPECT_NE(m.find(cut + ": truncated gzip file: the compressed data ends after "), std::string::npos) << m;
  EXPECT_NE(m.find(", after line "), std::string::npos) << m;
}

TEST_F(GzipFiles, ALogCutShortKeepsWhatWasReadAndSaysTheEndIsMissing) {
  const std::string text = noisyImuCsv(20000);
  const std::string whole = writeGzip("log.gz", text);
  const MaybeCutText all = readMaybeGzipLog(whole, kWholeLogLimit);
  EXPECT_FALSE(all.end_missing);
  EXPECT_EQ(all.text, text);
  const MaybeCutText part = readMaybeGzipLog(
      cutCopy(whole, "cut.gz", static_cast<long>(std::filesystem::file_size(whole)) / 2), kWholeLogLimit);
  EXPECT_TRUE(part.end_missing);
  EXPECT_GT(part.text.size(), text.size() / 4);
  EXPECT_LT(part.text.size(), text.size());
  EXPECT_EQ(text.compare(0, part.text.size(), part.text), 0) << "a prefix of the whole text";
  // A plain file has no end to miss: as it is, even cut mid-line.
  const MaybeCutText plain = readMaybeGzipLog(writePlain("plain.log", "(1.0) can0 123#00\n(2.0) ca"), kWholeLogLimit);
  EXPECT_FALSE(plain.end_missing);
  EXPECT_EQ(plain.text, "(1.0) can0 123#00\n(2.0) ca");
}

TEST_F(GzipFiles, AFailedCrcOrLengthCheckIsACorruptFile) {
  const std::string whole = writeGzip("imu.csv.gz", noisyImuCsv(2000));
  const std::string bad_crc = flippedCopy(whole, "crc.csv.gz", -8);
  const std::string bad_length = flippedCopy(whole, "length.csv.gz", -2);
  for (const std::string& path : {bad_crc, bad_length}) {
    for (const std::string& m :
         {errorOf([&] { readImuCsv(path); }), errorOf([&] { readMaybeGzipFile(path, kWholeLogLimit); }),
          errorOf([&] { readMaybeGzipLog(path, kWholeLogLimit); })}) {
      EXPECT_NE(m.find(path + ": corrupt gzip file: incorrect "), std::string::npos) << m;
    }
  }
}

TEST_F(GzipFiles, ImuTimesBeyondInt64NanosecondsAreAnError) {
  // 9.3e9 s does not fit int64 ns: llround gave INT64_MIN for every row, all "duplicates".
  for (const char* t : {"9300000000", "-9300000000", "1e300"}) {
    const std::string path = writePlain(
        "far.csv", std::string("t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,9.8\n") + t + ",0,0,0,0,0,9.8\n");
    const std::string m = errorOf([&] { readImuCsv(path, MagColumns::kIgnored); });
    EXPECT_NE(m.find(path + ":3: column 't': time "), std::string::npos) << t << ": " << m;
    EXPECT_NE(m.find("beyond ±9e9 s"), std::string::npos) << m;
  }
  const std::string ok = writePlain("ok.csv", "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n8999999999.5,0,0,0,0,0,9.8\n");
  EXPECT_GT(readImuCsv(ok, MagColumns::kIgnored).at(0).t_ns, 8'999'999'999'000'000'000);
}

}  // namespace
}  // namespace headingd::files
