// The daemon's real logger set-up (setUpLogging) writing to stderr redirected into a real
// file: when JOURNAL_STREAM names that file (as systemd names the journal's stream), each line
// carries its sd-daemon priority prefix and no timestamp; otherwise, or when JOURNAL_STREAM
// names some other file (inherited by a child whose stderr was redirected), the plain
// timestamped pattern.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "headingd/daemon/system/journal_stream.hpp"
#include "headingd/daemon/system/logging.hpp"

namespace headingd::daemon {
namespace {

std::string devIno(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) throw std::runtime_error("stat " + file.string());
  return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
}

// stderr (descriptor 2) into `file` for the life of this object; JOURNAL_STREAM as given.
class StderrInto {
 public:
  StderrInto(const std::filesystem::path& file, const char* journal_stream) {
    std::fflush(stderr);
    saved_ = ::dup(STDERR_FILENO);
    std::FILE* f = std::fopen(file.c_str(), "w");
    if (saved_ < 0 || f == nullptr) throw std::runtime_error("redirect stderr");
    ::dup2(::fileno(f), STDERR_FILENO);
    std::fclose(f);
    if (journal_stream != nullptr) {
      ::setenv("JOURNAL_STREAM", journal_stream, 1);
    } else {
      ::unsetenv("JOURNAL_STREAM");
    }
  }
  ~StderrInto() {
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    ::unsetenv("JOURNAL_STREAM");
  }

 private:
  int saved_ = -1;
};

class Logging : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("headingd-logging-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    log_ = dir_ / "stderr.txt";
    std::ofstream(log_).flush();  // exists, so its device:inode can be named before redirection
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Sets up the logger as main() does (level debug) and logs one line at each level.
  std::vector<std::string> logOneOfEach(const char* journal_stream) {
    {
      StderrInto redirect(log_, journal_stream);
      LogConfig config;
      config.level = "debug";
      setUpLogging(config, "");
      spdlog::debug("gps: debug line");
      spdlog::info("gps: /dev/gps0 open at 9600 baud");
      spdlog::warn("gps: /dev/gps0: busy, held by gpsd (pid 812); retrying");
      spdlog::error("lcm: cannot publish");
      spdlog::critical("estimator: stalled");
      spdlog::default_logger()->flush();
    }
    std::ifstream in(log_);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  std::filesystem::path dir_;
  std::filesystem::path log_;
};

TEST_F(Logging, UnderTheJournalEachLineCarriesItsPriorityAndNoTimestamp) {
  const std::string names_the_file = devIno(log_);
  const auto lines = logOneOfEach(names_the_file.c_str());
  const std::vector<std::string> want{
      "<7>[debug] gps: debug line",
      "<6>[info] gps: /dev/gps0 open at 9600 baud",
      "<4>[warning] gps: /dev/gps0: busy, held by gpsd (pid 812); retrying",
      "<3>[error] lcm: cannot publish",
      "<2>[critical] estimator: stalled",
  };
  EXPECT_EQ(lines, want);
}

void expectPlainPattern(const std::vector<std::string>& lines) {
  ASSERT_EQ(lines.size(), 5u);
  const std::regex stamped(R"(\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{3} \[(debug|info|warning|error|critical)\] .+)");
  for (const auto& line : lines) {
    EXPECT_TRUE(std::regex_match(line, stamped)) << line;
    EXPECT_NE(line.front(), '<') << line;
  }
  EXPECT_NE(lines[2].find("[warning] gps: /dev/gps0: busy"), std::string::npos) << lines[2];
}

TEST_F(Logging, WithoutJournalStreamLinesAreTimestampedAndUnprefixed) { expectPlainPattern(logOneOfEach(nullptr)); }

TEST_F(Logging, AJournalStreamNamingAnotherFileIsNotTheJournal) {
  const auto other = dir_ / "journal-of-the-parent";
  std::ofstream(other).flush();
  expectPlainPattern(logOneOfEach(devIno(other).c_str()));
  expectPlainPattern(logOneOfEach("not-a-device-inode-pair"));
}

TEST(SdDaemonPriority, FollowsSdDaemonLevels) {
  EXPECT_EQ(sdDaemonPriority(spdlog::level::critical), 2);
  EXPECT_EQ(sdDaemonPriority(spdlog::level::err), 3);
  EXPECT_EQ(sdDaemonPriority(spdlog::level::warn), 4);
  EXPECT_EQ(sdDaemonPriority(spdlog::level::info), 6);
  EXPECT_EQ(sdDaemonPriority(spdlog::level::debug), 7);
  EXPECT_EQ(sdDaemonPriority(spdlog::level::trace), 7);
}

}  // namespace
}  // namespace headingd::daemon
