// headingd: the real-time heading and attitude daemon (daemon/README.md).
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <string>

#include "headingd/daemon/config/config.hpp"
#include "headingd/daemon/daemon.hpp"
#include "headingd/daemon/system/logging.hpp"

namespace {

using namespace headingd::daemon;

// Exit statuses (the unit's RestartPreventExitStatus= keeps a bad configuration from
// restarting in a loop).
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadConfig = 2;

long residentKb() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    long value = 0;
    if (key == "VmRSS:" && status >> value) return value;
    status.ignore(1 << 10, '\n');
  }
  return -1;
}

std::string summaryJson(const LoopSummary& s) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  char text[1024];
  std::snprintf(text, sizeof text,
                "{\"ticks\":%llu,\"deadline_misses\":%llu,\"tick_jitter_p50_us\":%.1f,\"tick_jitter_p99_us\":%.1f,"
                "\"tick_jitter_max_us\":%.1f,\"processing_p50_us\":%.1f,\"processing_p99_us\":%.1f,"
                "\"processing_max_us\":%.1f,\"sample_age_p50_us\":%.1f,\"sample_age_p99_us\":%.1f,"
                "\"sample_age_max_us\":%.1f,\"heading_published\":%llu,\"imu_published\":%llu,"
                "\"gps_published\":%llu,\"status_published\":%llu,\"publish_errors\":%llu,\"rss_kb\":%ld,"
                "\"max_rss_kb\":%ld}",
                static_cast<unsigned long long>(s.ticks), static_cast<unsigned long long>(s.deadline_misses),
                s.timing.jitter_p50_us, s.timing.jitter_p99_us, s.timing.jitter_max_us, s.timing.processing_p50_us,
                s.timing.processing_p99_us, s.timing.processing_max_us, s.timing.sample_age_p50_us,
                s.timing.sample_age_p99_us, s.timing.sample_age_max_us,
                static_cast<unsigned long long>(s.heading_published), static_cast<unsigned long long>(s.imu_published),
                static_cast<unsigned long long>(s.gps_published), static_cast<unsigned long long>(s.status_published),
                static_cast<unsigned long long>(s.publish_errors), residentKb(), usage.ru_maxrss);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"headingd: real-time heading and attitude from an IMU and GPS, published over LCM"};
  std::string config_path = "/etc/headingd/headingd.toml";
  std::string log_level;
  bool check_only = false;
  app.add_option("-c,--config", config_path, "configuration file (TOML; config/headingd.toml documents every key)")
      ->capture_default_str();
  app.add_flag("--check-config", check_only,
               "read and check the configuration and every file it names, then exit (0: good, 2: bad)");
  app.add_option("--log-level", log_level, "override [log] level")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  app.set_version_flag("--version", std::string("headingd ") + HEADINGD_VERSION);
  app.footer(
      "Exit status: 0 stopped by SIGINT/SIGTERM or at the end of the played logs (or --check-config: good), "
      "1 start-up failed after the checks (e.g. LCM cannot open), 2 bad command line, configuration or file "
      "it names (the unit does not restart then). A SIGTERM while the files are read at start-up ends the "
      "process at once (killed by the signal).");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // One status for any bad option (not CLI11's own 100..114), the one the unit does not restart on.
    return app.exit(e) == 0 ? kExitOk : kExitBadConfig;
  }

  // Signals are taken synchronously by this thread (sigtimedwait below), blocked before any
  // thread starts, so every thread inherits the mask and none is interrupted by them. During
  // the checks of start-up (one thread only) SIGINT and SIGTERM keep their default action, so
  // a start-up held up by a slow file still ends at once; SIGHUP waits until the daemon runs.
  sigset_t hangup;
  sigemptyset(&hangup);
  sigaddset(&hangup, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &hangup, nullptr);
  sigset_t signals = hangup;
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);

  DaemonConfig config;
  try {
    config = loadDaemonConfig(config_path);
    setUpLogging(config.log, log_level);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd: %s\n", e.what());
    return kExitBadConfig;
  }

  // Every check of start-up, --check-config or not (daemon.hpp).
  std::unique_ptr<Daemon> daemon;
  try {
    daemon = std::make_unique<Daemon>(config);
  } catch (const headingd::core::ConfigError& e) {
    spdlog::critical("{}", e.what());
    return kExitBadConfig;
  } catch (const std::exception& e) {
    spdlog::critical("{}: {}", config_path, e.what());
    return kExitBadConfig;
  }
  if (check_only) {
    std::printf("%s: configuration good (%zu source(s), estimator at %g Hz, LCM %s)\n", config_path.c_str(),
                daemon->sourceCount(), config.rate_hz, config.lcm.url.c_str());
    return kExitOk;
  }

  pthread_sigmask(SIG_BLOCK, &signals, nullptr);  // before the first thread
  try {
    daemon->start();
  } catch (const std::exception& e) {
    spdlog::critical("start-up failed: {}", e.what());
    return kExitFailure;
  }

  // Waits for a signal or for the loop to end by itself; the timeout bounds how late an
  // ending loop is noticed.
  const timespec poll{0, 50'000'000};
  for (;;) {
    siginfo_t info{};
    const int s = sigtimedwait(&signals, &info, &poll);
    if (s == SIGINT || s == SIGTERM) {
      spdlog::info("{}: stopping", s == SIGINT ? "SIGINT" : "SIGTERM");
      break;
    }
    if (s == SIGHUP) {
      spdlog::info("SIGHUP: reopening the log file, reloading the calibration");
      reopenLogFile();
      daemon->requestCalibrationReload();
    }
    if (daemon->finished()) break;
  }
  daemon->stop();
  spdlog::info("summary {}", summaryJson(daemon->summary()));
  return kExitOk;
}
