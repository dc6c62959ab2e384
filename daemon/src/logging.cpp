#include "headingd/daemon/logging.hpp"

#include <cstdlib>
#include <mutex>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/dist_sink.h>
#include <spdlog/sinks/stdout_sinks.h>

namespace headingd::daemon {
namespace {

std::mutex g_mutex;
std::shared_ptr<spdlog::sinks::dist_sink_mt> g_dist;
std::shared_ptr<spdlog::sinks::sink> g_stderr;
std::string g_file;

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
  g_stderr->set_pattern(std::getenv("JOURNAL_STREAM") != nullptr ? "[%l] %v" : "%Y-%m-%d %H:%M:%S.%e [%l] %v");
  g_dist = std::make_shared<spdlog::sinks::dist_sink_mt>();
  g_file = config.file;
  installSinks();
  auto logger = std::make_shared<spdlog::logger>("headingd", g_dist);
  logger->set_level(spdlog::level::from_str(level_override.empty() ? config.level : level_override));
  logger->flush_on(spdlog::level::trace);  // a daemon's log is read live; lines are few
  spdlog::set_default_logger(logger);
}

void reopenLogFile() {
  std::lock_guard lock(g_mutex);
  if (g_dist == nullptr || g_file.empty()) return;
  installSinks();
}

}  // namespace headingd::daemon
