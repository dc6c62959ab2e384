#pragma once
// [nmea_out] as an estimate sink: every round(rate_hz / [nmea_out] rate_hz) estimates, the
// estimate goes out as NMEA sentences through the server's own thread (nmea_out_server.hpp);
// its counters go on STATUS.
#include <cstdint>

#include "headingd/daemon/outputs/estimate_sink.hpp"
#include "headingd/daemon/outputs/nmea_out_config.hpp"
#include "headingd/daemon/outputs/nmea_out_sentences.hpp"
#include "headingd/daemon/outputs/nmea_out_server.hpp"

namespace headingd::daemon {

class NmeaOutput final : public EstimateSink {
 public:
  // `config` and `server` are borrowed. `estimate_rate_hz`: the loop's rate ([daemon] rate_hz);
  // `from_files`: the inputs are files, a replay, so THS says S (simulator).
  NmeaOutput(const NmeaOutConfig& config, double estimate_rate_hz, NmeaOutServer& server, bool from_files);

  void estimate(const PublishedEstimate& estimate) override;
  void appendStatusCounters(status_t& m) const override;

 private:
  const NmeaOutConfig& config_;
  NmeaOutServer& server_;
  bool from_files_;
  std::uint64_t every_estimates_;
  std::uint64_t estimates_to_next_ = 0;
  NmeaOutBatch batch_;
};

}  // namespace headingd::daemon
