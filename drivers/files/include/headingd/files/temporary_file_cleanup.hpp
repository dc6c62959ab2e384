#pragma once
// Temporary output files removed when the process is killed by SIGINT, SIGTERM, SIGHUP or
// SIGQUIT (Ctrl-C on a long replay, a timeout), so that an interrupted tool leaves neither a
// half-written output nor its ".NAME.XXXXXX" temporary behind. The handlers are installed only
// for signals whose disposition is still the default (a program with handlers of its own, such
// as the daemon, keeps them); after removing the files, the handler restores the default and
// raises the signal again, so the process still ends as killed by it.
namespace headingd::files {

// Up to kMaxTemporaryFiles paths at once (more are not registered: they may be left behind).
inline constexpr int kMaxTemporaryFiles = 64;

// Returns a slot to pass to forget..., or -1 when none is free or the path is too long.
int removeOnFatalSignal(const char* path);
void forgetOnFatalSignal(int slot);

}  // namespace headingd::files
