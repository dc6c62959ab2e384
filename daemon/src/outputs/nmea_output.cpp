#include "headingd/daemon/outputs/nmea_output.hpp"

#include <algorithm>
#include <cmath>

namespace headingd::daemon {

NmeaOutput::NmeaOutput(const NmeaOutConfig& config, double estimate_rate_hz, NmeaOutServer& server, bool from_files)
    : config_(config),
      server_(server),
      from_files_(from_files),
      every_estimates_(static_cast<std::uint64_t>(std::max(1LL, std::llround(estimate_rate_hz / config.rate_hz)))) {}

void NmeaOutput::estimate(const PublishedEstimate& e) {
  if (estimates_to_next_ > 0) {
    --estimates_to_next_;
    return;
  }
  estimates_to_next_ = every_estimates_ - 1;
  formatNmeaOut(config_, e.pipeline.output(), e.validity, from_files_, batch_);
  server_.offer(batch_);
}

void NmeaOutput::appendStatusCounters(status_t& m) const {
  const NmeaOutCounters counters = server_.counters();  // "nmea_out_clients", ...
  daemon::appendStatusCounters(m, [&](const auto& add) { forEachNmeaOutCounter(counters, add); });
}

}  // namespace headingd::daemon
