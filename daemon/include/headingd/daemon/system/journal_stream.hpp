#pragma once
// Is stderr the systemd journal? systemd sets JOURNAL_STREAM="DEV:INODE" (decimal) for a
// service whose stdout/stderr it connects to the journal; the variable is inherited by
// children whose stderr may point elsewhere, so it counts only when it names the file stderr
// really is (fstat), as systemd.exec(5) and sd_journal_stream_fd(3) recommend.
#include <spdlog/common.h>

namespace headingd::daemon {

// True when `journal_stream` (the variable's value, may be null) names the file open on `fd`.
bool journalStreamNames(const char* journal_stream, int fd);
// The same for this process: getenv("JOURNAL_STREAM") against stderr.
bool stderrIsJournal();

// The sd-daemon(3) priority a line carries as its "<N>" prefix, from the spdlog level:
// critical 2 (SD_CRIT), error 3 (SD_ERR), warning 4 (SD_WARNING), info 6 (SD_INFO),
// debug and trace 7 (SD_DEBUG).
int sdDaemonPriority(spdlog::level::level_enum level);

}  // namespace headingd::daemon
