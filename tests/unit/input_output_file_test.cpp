// files/input_file.hpp and files/output_file.hpp on real files: what cannot stall or flood a
// reader (a FIFO without a writer, /dev/zero, a directory, a file over its limit, a gzip bomb,
// a file without line breaks) is refused with a message naming the file, and an output
// appears under its name only when whole.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>

#include "headingd/files/gzip_file.hpp"
#include "headingd/files/input_file.hpp"
#include "headingd/files/line_reader.hpp"
#include "headingd/files/output_file.hpp"
#include "temp_csv_files.hpp"

namespace headingd::files {
namespace {

using InputFiles = TempCsvFiles;
using OutputFiles = TempCsvFiles;

std::string contents(const std::string& path) { return readWholeFile(path, 0); }

TEST_F(InputFiles, AFifoWithoutWriterIsRefusedAtOnceNotWaitedFor) {
  const std::string fifo = (dir_ / "calibration.toml").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Before: an open for reading waited for a writer, for ever.
  EXPECT_EQ(inputFileProblem(fifo, kConfigFileLimit), fifo + ": is a FIFO (named pipe), not a regular file");
  EXPECT_NE(messageOf([&] { readMaybeGzipFile(fifo, kConfigFileLimit); }).find("FIFO"), std::string::npos);
  EXPECT_NE(messageOf([&] { LineReader lines(fifo); }).find("FIFO"), std::string::npos);
}

TEST_F(InputFiles, DevZeroAndDirectoriesAreRefused) {
  // Before: /dev/zero as the WMM file was read until the OOM killer acted.
  EXPECT_EQ(inputFileProblem("/dev/zero", kWmmFileLimit), "/dev/zero: is a character device, not a regular file");
  EXPECT_NE(messageOf([] { readMaybeGzipFile("/dev/zero", kWmmFileLimit); }).find("character device"),
            std::string::npos);
  EXPECT_EQ(inputFileProblem(dir_.string(), 0), dir_.string() + ": is a directory, not a file");
  EXPECT_NE(messageOf([&] { readWholeFile((dir_ / "missing").string(), 10); }).find("No such file"), std::string::npos);
}

TEST_F(InputFiles, AFileOverItsLimitIsRefusedAndOneWithinIsReadWhole) {
  const std::string path = writePlain("wmm.cof", std::string(3000, 'x'));
  EXPECT_EQ(readWholeFile(path, 3000).size(), 3000u);
  EXPECT_EQ(inputFileProblem(path, 3000), "");
  EXPECT_EQ(inputFileProblem(path, 2048), path + ": is 3000 bytes, more than the 2 kiB such a file may have");
  EXPECT_NE(messageOf([&] { readWholeFile(path, 2048); }).find("more than the 2 kiB"), std::string::npos);
}

TEST_F(InputFiles, AGzipFileThatInflatesBeyondTheLimitIsRefused) {
  // 4 MiB of zeros is a few kB of gzip: the limit holds for what it inflates to.
  const std::string path = writeGzip("calibration.toml.gz", std::string(4 * kMiB, '\0'));
  ASSERT_LT(std::filesystem::file_size(path), kConfigFileLimit);
  EXPECT_NE(messageOf([&] { readMaybeGzipFile(path, kConfigFileLimit); }).find("holds more than the 1 MiB"),
            std::string::npos);
  EXPECT_EQ(readMaybeGzipFile(path, 8 * kMiB).size(), 4 * kMiB);
}

TEST_F(InputFiles, ALineLongerThanTheLimitIsRefusedWithItsNumber) {
  const std::string path = writePlain("log.csv", "t,x\n1,2\n" + std::string(kMaxLineBytes + 1, '7') + "\n3,4\n");
  LineReader lines(path);
  std::string_view line;
  ASSERT_TRUE(lines.next(&line));
  ASSERT_TRUE(lines.next(&line));
  EXPECT_EQ(line, "1,2");
  EXPECT_EQ(messageOf([&] { lines.next(&line); }),
            path + ":3: a line longer than 1 MiB (no line break): not a text file of this kind");
  // Up to the limit a line is read whole.
  LineReader long_lines(writePlain("long.csv", std::string(kMaxLineBytes - 1, '7') + "\n"));
  ASSERT_TRUE(long_lines.next(&line));
  EXPECT_EQ(line.size(), kMaxLineBytes - 1);
}

TEST_F(OutputFiles, TheFileAppearsOnlyWhenCommittedAndAnEarlierOneStaysUntilThen) {
  const std::string path = writePlain("out.csv", "earlier\n");
  {
    OutputFile out(path);
    out.write("half a resu");
    EXPECT_EQ(contents(path), "earlier\n");
  }  // not committed: an error stopped the run
  EXPECT_EQ(contents(path), "earlier\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator()), 1)
      << "the temporary file is removed";
  OutputFile out(path);
  out.write("new\n");
  out.commit();
  EXPECT_EQ(contents(path), "new\n");
}

// A tool killed while writing (Ctrl-C, a timeout's SIGTERM) leaves no temporary file behind,
// and still dies of the signal (its parent sees that, not a normal exit).
TEST_F(OutputFiles, AKilledRunLeavesNoTemporaryFile) {
  for (const int signal_number : {SIGINT, SIGTERM}) {
    const std::string path = writePlain("kept.csv", "earlier\n");
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      OutputFile out(path);
      out.write("half a resu");
      std::fflush(out.stream());
      ::raise(signal_number);
      ::_exit(0);  // not reached
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal_number) << "status " << status;
    EXPECT_EQ(contents(path), "earlier\n");
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator()), 1)
        << "a temporary file is left";
  }
}

TEST_F(OutputFiles, ANewFileIsCreatedWithTheUsualMode) {
  const std::string path = (dir_ / "new.csv").string();
  writeWholeOutputFile(path, "t\n");
  EXPECT_EQ(contents(path), "t\n");
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(static_cast<mode_t>(std::filesystem::status(path).permissions()) & 0777, 0666 & ~mask);
}

TEST_F(OutputFiles, ALinkedOutputReplacesTheTargetNotTheLink) {
  const std::string target = writePlain("target.csv", "old\n");
  const std::string link = (dir_ / "link.csv").string();
  std::filesystem::create_symlink(target, link);
  writeWholeOutputFile(link, "new\n");
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(contents(target), "new\n");
}

TEST_F(OutputFiles, NonRegularOutputsAreWrittenDirectly) {
  writeWholeOutputFile("/dev/null", "discarded\n");
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/null"));
  EXPECT_NE(messageOf([&] { writeWholeOutputFile(dir_.string(), "x"); }).find("is a directory"), std::string::npos);
}

TEST_F(OutputFiles, AnOutputThatIsAnInputIsRefusedAlsoThroughLinks) {
  const std::string input = writeGzip("trial.csv.gz", "t\n1\n");
  const std::string symlink = (dir_ / "symlink.csv.gz").string();
  const std::string hardlink = (dir_ / "hardlink.csv.gz").string();
  std::filesystem::create_symlink(input, symlink);
  std::filesystem::create_hard_link(input, hardlink);
  for (const std::string& out : {input, symlink, hardlink}) {
    EXPECT_EQ(messageOf([&] {
                refuseOutputOverInputs({"--out", out}, {{"--config", ""}, {"--imu-csv", input}});
              }),
              "--out '" + out + "' is the same file as --imu-csv '" + input + "': refusing to overwrite an input");
  }
  EXPECT_EQ(messageOf([&] {
              refuseOutputOverInputs({"--out", (dir_ / "new.csv").string()}, {{"--imu-csv", input}});
            }),
            "");
}

}  // namespace
}  // namespace headingd::files
