#include "headingd/daemon/sources/source.hpp"

namespace headingd::daemon {

const char* sourceStateName(SourceState s) {
  switch (s) {
    case SourceState::kStarting: return "starting";
    case SourceState::kRunning: return "running";
    case SourceState::kWaiting: return "waiting";
    case SourceState::kFinished: return "finished";
    case SourceState::kError: return "error";
  }
  return "?";
}

void SourceReport::set(std::size_t i, std::string_view name, std::uint64_t value) { set(i, {}, name, value); }

void SourceReport::set(std::size_t i, std::string_view prefix, std::string_view name, std::uint64_t value) {
  if (i >= counters.size()) counters.resize(i + 1);
  std::string& current = counters[i].name;
  // Rewritten only when it changes, so a report refilled every second does not allocate.
  const bool same = current.size() == prefix.size() + name.size() && current.compare(0, prefix.size(), prefix) == 0 &&
                    current.compare(prefix.size(), name.size(), name) == 0;
  if (!same) {
    current.assign(prefix);
    current.append(name);
  }
  counters[i].value = value;
}

}  // namespace headingd::daemon
