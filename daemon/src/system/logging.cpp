#include "headingd/daemon/system/logging.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/dist_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <atomic>
#include <mutex>

#include "headingd/daemon/system/journal_stream.hpp"

namespace headingd::daemon {
namespace {

// Under the journal each line starts with its sd-daemon(3) priority ("<4>[warning] ..."),
// which journald strips and stores as the entry's PRIORITY (SyslogLevelPrefix=, on by
// default), so `journalctl -p warning` finds warnings and errors. Chosen over spdlog's
// systemd_sink (sd_journal_send; Debian 12's spdlog 1.10 has it): the prefix keeps a single
// stream on stderr, in order with anything else written there (the C++ runtime's last words
// before an abort, libraries' own prints), needs no second connection to journald (a
// sandbox or container may not give one, and sd_journal_send then drops lines silently),
// and is what the test reads back from a file.
class SdDaemonPriorityFlag final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
    const char prefix[3] = {'<', static_cast<char>('0' + sdDaemonPriority(msg.level)), '>'};
    dest.append(prefix, prefix + 3);
  }
  std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<SdDaemonPriorityFlag>(); }
};

// The journal stamps each entry itself: no timestamp of our own there.
std::unique_ptr<spdlog::formatter> stderrFormatter() {
  auto f = std::make_unique<spdlog::pattern_formatter>();
  if (stderrIsJournal()) {
    f->add_flag<SdDaemonPriorityFlag>('*').set_pattern("%*[%l] %v");
  } else {
    f->set_pattern("%Y-%m-%d %H:%M:%S.%e [%l] %v");
  }
  return f;
}

std::mutex g_mutex;
std::shared_ptr<spdlog::sinks::dist_sink_mt> g_dist;
std::shared_ptr<spdlog::sinks::sink> g_stderr;
std::string g_file;
std::atomic<std::uint64_t> g_write_errors{0};
std::atomic<bool> g_write_error_said{false};  // since the file was last (re)opened

// spdlog calls this when a sink throws: the log file's write or flush failed (a full disk,
// an I/O error). stderr has the line already (it is the first sink), so nothing is lost
// there; the failure is counted for STATUS and said on stderr once per opening of the file,
// instead of spdlog's default of one message a second on the wall clock.
void onSinkError(const std::string& what) {
  g_write_errors.fetch_add(1, std::memory_order_relaxed);
  if (g_write_error_said.exchange(true) || g_stderr == nullptr) return;
  const std::string text = "log file: " + what +
                           "; lines go to stderr only until it can be written again (counted on STATUS as "
                           "log_write_errors; said once until SIGHUP reopens the file)";
  g_stderr->log(spdlog::details::log_msg("headingd", spdlog::level::err, text));
}

void installSinks() {
  std::vector<std::shared_ptr<spdlog::sinks::sink>> sinks{g_stderr};
  if (!g_file.empty()) {
    auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(g_file, false);
    file->set_pattern("%Y-%m-%d %H:%M:%S.%e [%l] %v");
    sinks.push_back(file);
  }
  g_dist->set_sinks(std::move(sinks));  // dist_sink swaps under its own lock
}

}  // namespace

void setUpLogging(const LogConfig& config, const std::string& level_override) {
  std::lock_guard lock(g_mutex);
  g_stderr = std::make_shared<spdlog::sinks::stderr_sink_mt>();
  g_stderr->set_formatter(stderrFormatter());
  g_dist = std::make_shared<spdlog::sinks::dist_sink_mt>();
  g_file = config.file;
  installSinks();
  auto logger = std::make_shared<spdlog::logger>("headingd", g_dist);
  logger->set_error_handler(onSinkError);
  logger->set_level(spdlog::level::from_str(level_override.empty() ? config.level : level_override));
  logger->flush_on(spdlog::level::trace);  // a daemon's log is read live; lines are few
  spdlog::set_default_logger(logger);
}

void reopenLogFile() {
  std::string failure;
  {
    std::lock_guard lock(g_mutex);
    if (g_dist == nullptr || g_file.empty()) return;
    g_write_error_said.store(false);
    try {
      installSinks();
    } catch (const std::exception& e) {  // e.g. its folder is gone: go on with stderr alone
      g_dist->set_sinks({g_stderr});
      g_write_errors.fetch_add(1, std::memory_order_relaxed);
      failure = e.what();
    }
  }
  if (!failure.empty()) spdlog::error("log file not reopened, logging to stderr only: {}", failure);
}

std::uint64_t logWriteErrors() { return g_write_errors.load(std::memory_order_relaxed); }

}  // namespace headingd::daemon
