#pragma once
// gpsd as the GPS source ([gps] source = "gpsd"): drivers/gpsd's GpsdClient on an io_context
// of its own thread; each receiver epoch goes into the GPS ring like the serial source's,
// stamped with its monotonic receive time, the TPV's UTC beside it in the fix.
#include <memory>

#include "headingd/daemon/asio_source.hpp"
#include "headingd/daemon/repeat_limiter.hpp"
#include "headingd/daemon/ring_entries.hpp"
#include "headingd/daemon/source_registry.hpp"
#include "headingd/gpsd/gpsd_client.hpp"

namespace headingd::daemon {

struct GpsdGpsSourceConfig : SourceConfig {
  gpsd::GpsdConfig gpsd;
};
std::unique_ptr<SourceConfig> parseGpsdGpsSource(const SourceTable& table);
std::unique_ptr<Source> createGpsdGpsSource(const SourceConfig& config, SourceContext& context);

class GpsdGpsSource final : public AsioSource<gpsd::GpsdCounters> {
 public:
  GpsdGpsSource(std::string name, const gpsd::GpsdConfig& config, std::uint16_t source_index,
                SampleRing<GpsRingEntry>* gps_ring);
  ~GpsdGpsSource() override;

  const char* kind() const override { return "gps_gpsd"; }
  void report(SourceReport& out) const override;
  // gpsd's reports come as the receiver sends them, and their arrival time places the epoch:
  // a driver thread, as the serial source's.
  bool readsAtRealTimePace() const override { return true; }

 private:
  void onStart() override { client_->start(); }
  void onStop() override;
  gpsd::GpsdCounters currentCounters() const override { return client_->counters(); }
  void onFix(const nmea::Fix& fix, std::int64_t receive_ns);
  void onProblem(std::string_view kind, const std::string& detail);

  SampleRing<GpsRingEntry>* ring_;
  std::unique_ptr<gpsd::GpsdClient> client_;
  RepeatLimiter problem_log_{5, 10.0};  // io thread
};

}  // namespace headingd::daemon
