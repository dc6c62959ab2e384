// The test fixture's ChildProcess: a test process that dies takes its daemon with it.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "daemon_test_support.hpp"

namespace headingd::daemon::test {
namespace {

// Gone, or a zombie waiting for whoever adopted it: either way no longer running.
bool processEnded(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  if (!stat) return true;
  std::string text((std::istreambuf_iterator<char>(stat)), {});
  const std::size_t after_name = text.rfind(')');  // the name may hold spaces and parentheses
  return after_name == std::string::npos || text.substr(after_name + 2, 1) == "Z" ||
         text.substr(after_name + 2, 1) == "X";
}

TEST(ChildProcess, DiesWithTheProcessThatStartedItEvenWithoutItsDestructor) {
  TempDir dir;
  int pid_pipe[2];
  ASSERT_EQ(pipe(pid_pipe), 0);
  const pid_t test_process = fork();  // stands for a test process that crashes
  ASSERT_GE(test_process, 0);
  if (test_process == 0) {
    close(pid_pipe[0]);
    pid_t child = -1;
    try {
      auto* sleeper = new ChildProcess({"/bin/sleep", "60"}, dir.file("out"), dir.file("err"));
      child = sleeper->pid();
    } catch (...) {
    }
    (void)!write(pid_pipe[1], &child, sizeof child);
    _exit(0);  // no destructor runs, as in a crash
  }
  close(pid_pipe[1]);
  pid_t child = -1;
  ASSERT_EQ(read(pid_pipe[0], &child, sizeof child), static_cast<ssize_t>(sizeof child));
  close(pid_pipe[0]);
  ASSERT_GT(child, 0) << "the sleeper did not start";
  waitpid(test_process, nullptr, 0);
  EXPECT_TRUE(waitUntil([&] { return processEnded(child); }, std::chrono::seconds(5)))
      << "pid " << child << " outlived the process that started it";
  if (!processEnded(child)) kill(child, SIGKILL);
}

TEST(ChildProcess, ABinaryThatCannotBeRunIsAnErrorNamingIt) {
  TempDir dir;
  try {
    ChildProcess missing({dir.file("no-such-binary")}, dir.file("out"), dir.file("err"));
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-binary"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace headingd::daemon::test
