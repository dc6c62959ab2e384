#include "headingd/daemon/system/journal_stream.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>

namespace headingd::daemon {

bool journalStreamNames(const char* journal_stream, int fd) {
  if (journal_stream == nullptr) return false;
  std::uintmax_t dev = 0, ino = 0;
  char trailing = 0;
  if (std::sscanf(journal_stream, "%" SCNuMAX ":%" SCNuMAX "%c", &dev, &ino, &trailing) != 2) return false;
  struct stat st {};
  if (::fstat(fd, &st) != 0) return false;
  return static_cast<std::uintmax_t>(st.st_dev) == dev && static_cast<std::uintmax_t>(st.st_ino) == ino;
}

bool stderrIsJournal() { return journalStreamNames(std::getenv("JOURNAL_STREAM"), STDERR_FILENO); }

int sdDaemonPriority(spdlog::level::level_enum level) {
  switch (level) {
    case spdlog::level::critical: return 2;
    case spdlog::level::err: return 3;
    case spdlog::level::warn: return 4;
    case spdlog::level::info: return 6;
    case spdlog::level::debug:
    case spdlog::level::trace: return 7;
    case spdlog::level::off:
    case spdlog::level::n_levels: break;
  }
  return 6;
}

}  // namespace headingd::daemon
