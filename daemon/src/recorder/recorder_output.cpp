#include "headingd/daemon/recorder/recorder_output.hpp"

namespace headingd::daemon {

void appendRecorderCounters(status_t& m, const RecorderCounters& recorder) {
  appendStatusCounters(m, [&](const auto& add) { forEachRecorderCounter(recorder, add); });
}

void RecorderOutput::appendStatusCounters(status_t& m) const { appendRecorderCounters(m, recorder_.counters()); }

}  // namespace headingd::daemon
