#pragma once
// The serial GPS receiver as a source: drivers/nmea's SerialGpsReader on an io_context of
// its own thread; each completed epoch goes into the GPS ring, stamped with its monotonic
// receive time (the IMU's time axis for live sources).
#include <memory>

#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/sources/gps_fix_source.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/nmea/serial_gps_config.hpp"
#include "headingd/nmea/serial_gps_reader.hpp"

namespace headingd::daemon {

// [gps], read by drivers/nmea's own loader (serial_gps_config.hpp); enabled = false there
// keeps the table without a source.
struct SerialGpsSourceConfig : SourceConfig {
  explicit SerialGpsSourceConfig(nmea::SerialGpsConfig settings) : gps(std::move(settings)) { enabled = gps.enabled; }
  nmea::SerialGpsConfig gps;
  std::unique_ptr<Source> createSource(SourceContext& context) const override;
};

class SerialGpsSource final : public GpsFixSource<nmea::SerialGpsReader> {
 public:
  SerialGpsSource(std::string name, const nmea::SerialGpsConfig& config, std::uint16_t source_index,
                  SampleRing<GpsRingEntry>* gps_ring, const RecorderSinks* recorder = nullptr);
  ~SerialGpsSource() override;

  const char* kind() const override { return "gps_serial"; }
  void report(SourceReport& out) const override;

 private:
  std::unique_ptr<recording::GpsStreamRecorder> recorder_;  // null: not recording
};

}  // namespace headingd::daemon
