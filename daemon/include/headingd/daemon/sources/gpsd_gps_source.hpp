#pragma once
// gpsd as the GPS source ([gps] source = "gpsd"): drivers/gpsd's GpsdClient on an io_context
// of its own thread; each receiver epoch goes into the GPS ring like the serial source's,
// stamped with its monotonic receive time, the TPV's UTC beside it in the fix.
#include <memory>

#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/sources/gps_fix_source.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/daemon/system/repeat_limiter.hpp"
#include "headingd/gpsd/gpsd_client.hpp"

namespace headingd::daemon {

struct GpsdGpsSourceConfig : SourceConfig {
  explicit GpsdGpsSourceConfig(gpsd::GpsdConfig settings) : gpsd(std::move(settings)) { enabled = gpsd.enabled; }
  gpsd::GpsdConfig gpsd;
  std::unique_ptr<Source> createSource(SourceContext& context) const override;
};

class GpsdGpsSource final : public GpsFixSource<gpsd::GpsdClient> {
 public:
  GpsdGpsSource(std::string name, const gpsd::GpsdConfig& config, std::uint16_t source_index,
                SampleRing<GpsRingEntry>* gps_ring);
  ~GpsdGpsSource() override;

  const char* kind() const override { return "gps_gpsd"; }
  void report(SourceReport& out) const override;

 private:
  void onProblem(std::string_view kind, const std::string& detail);

  RepeatLimiter problem_log_{10, 10.0};  // io thread
};

}  // namespace headingd::daemon
