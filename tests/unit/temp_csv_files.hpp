#pragma once
// A fresh temporary folder per test, with helpers to write plain and gzip files into it: the
// CSV reader tests read real files.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

namespace headingd::files {

// The message of the `Error` that `f` throws, "" when it throws none (any other exception goes
// on up).
template <class Error = std::exception, class F>
std::string messageOf(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

class TempCsvFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("headingd-csv-" + std::to_string(::getpid()) + "-" + info->test_suite_name() + "-" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string writePlain(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.close();
    EXPECT_TRUE(out) << path;
    return path.string();
  }

  std::string writeGzip(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    gzFile file = gzopen(path.c_str(), "wb");
    EXPECT_NE(file, nullptr) << path;
    if (file == nullptr) return path.string();
    if (!text.empty()) {
      EXPECT_EQ(gzwrite(file, text.data(), static_cast<unsigned>(text.size())), static_cast<int>(text.size()));
    }
    EXPECT_EQ(gzclose(file), Z_OK);
    return path.string();
  }

  std::filesystem::path dir_;
};

}  // namespace headingd::files
