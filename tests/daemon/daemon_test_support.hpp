#pragma once
// Real files in a fresh temporary folder, and a child process for the daemon binary.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace headingd::daemon::test {

class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "headingd-daemon-test-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }

 private:
  std::string path_;
};

inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A process started with fork and exec, stdout and stderr to files. It dies with the thread
// that started it (PR_SET_PDEATHSIG): a test process that crashes or is killed by ctest's
// timeout takes its daemon with it, instead of leaving it running and holding the ptys,
// ports and files that later tests reuse. So start a ChildProcess from the test's own thread
// (a thread that ends kills its children).
class ChildProcess {
 public:
  ChildProcess(const std::vector<std::string>& argv, const std::string& stdout_path, const std::string& stderr_path,
               const std::vector<std::string>& extra_env = {}) {
    // Everything the child needs is made before fork: between fork and exec, a child of a
    // threaded process may only make async-signal-safe calls (no allocation).
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::vector<std::string> env_strings;
    for (char** e = environ; *e != nullptr; ++e) env_strings.emplace_back(*e);
    for (const auto& e : extra_env) env_strings.push_back(e);
    std::vector<char*> env;
    for (auto& e : env_strings) env.push_back(e.data());
    env.push_back(nullptr);
    // A pipe closed by a successful exec: an error number written to it says exec failed.
    int exec_failed[2];
    if (pipe2(exec_failed, O_CLOEXEC) != 0) throw std::runtime_error("pipe2 failed");
    const pid_t parent = getpid();
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("fork for " + argv[0] + " failed");
    if (pid_ == 0) {
      // If the parent died before the prctl, no signal would come: check, and go.
      if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent) _exit(127);
      const int out = open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      const int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (out < 0 || err < 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0) _exit(127);
      execve(args[0], args.data(), env.data());
      const int error = errno;
      (void)!write(exec_failed[1], &error, sizeof error);
      _exit(127);
    }
    close(exec_failed[1]);
    int error = 0;
    const ssize_t n = read(exec_failed[0], &error, sizeof error);
    close(exec_failed[0]);
    if (n > 0) {
      waitpid(pid_, nullptr, 0);
      pid_ = -1;
      throw std::runtime_error("cannot run " + argv[0] + ": " + std::strerror(error));
    }
  }
  ~ChildProcess() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  pid_t pid() const { return pid_; }
  void signal(int s) const { kill(pid_, s); }
  // Exit status, or -1 if it has not exited within `timeout` (-2: killed by a signal).
  int waitFor(std::chrono::milliseconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      int status = 0;
      const pid_t r = waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
      }
      if (std::chrono::steady_clock::now() >= until) return -1;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
};

// An LCM URL on a port of this process's own (the group and ttl=0 stay): tests running at
// the same time, here or in another build, do not hear each other.
#ifdef HEADINGD_CONFIG_DIR
// The demo capture (config/demo/README.md): the CAN IMU frames as a candump log, the GPS as NMEA.
inline constexpr const char* kDemoCan = HEADINGD_CONFIG_DIR "/demo/sim-urban-walk-can.log.gz";
inline constexpr const char* kDemoNmea = HEADINGD_CONFIG_DIR "/demo/sim-urban-walk.nmea";
// BROAD trial 05 as an IMU CSV (config/demo/README.md), the daemon tests' usual [imu_csv].
inline constexpr const char* kDemoImuCsv =
    HEADINGD_CONFIG_DIR "/demo/05_undisturbed_slow_rotation_with_breaks_B.csv.gz";
#endif

inline std::string lcmUrl(int offset) {
  return "udpm://239.255.76.67:" + std::to_string(20000 + (getpid() % 20000) * 2 + offset) + "?ttl=0";
}

// Waits until `predicate` holds or `timeout` passes.
template <class P>
bool waitUntil(P predicate, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    if (predicate()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return predicate();
}

}  // namespace headingd::daemon::test
