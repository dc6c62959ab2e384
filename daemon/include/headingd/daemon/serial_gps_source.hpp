#pragma once
// The serial GPS receiver as a source: drivers/nmea's SerialGpsReader on an io_context of
// its own thread; each completed epoch goes into the GPS ring, stamped with its monotonic
// receive time (the IMU's time axis for live sources).
#include <memory>

#include "headingd/daemon/asio_source.hpp"
#include "headingd/daemon/ring_entries.hpp"
#include "headingd/daemon/source_registry.hpp"
#include "headingd/nmea/serial_gps_config.hpp"
#include "headingd/nmea/serial_gps_reader.hpp"

namespace headingd::daemon {

// [gps], read by drivers/nmea's own loader (serial_gps_config.hpp); enabled = false there
// keeps the table without a source.
struct SerialGpsSourceConfig : SourceConfig {
  nmea::SerialGpsConfig gps;
};
std::unique_ptr<SourceConfig> parseSerialGpsSource(const SourceTable& table);
std::unique_ptr<Source> createSerialGpsSource(const SourceConfig& config, SourceContext& context);

class SerialGpsSource final : public AsioSource<nmea::SerialGpsCounters> {
 public:
  SerialGpsSource(std::string name, const nmea::SerialGpsConfig& config, std::uint16_t source_index,
                  SampleRing<GpsRingEntry>* gps_ring, const RecorderSinks* recorder = nullptr);
  ~SerialGpsSource() override;

  const char* kind() const override { return "gps_serial"; }
  bool readsAtRealTimePace() const override { return true; }
  void report(SourceReport& out) const override;

 private:
  void onStart() override { reader_->start(); }
  void onStop() override;
  nmea::SerialGpsCounters currentCounters() const override { return reader_->counters(); }
  void onFix(const nmea::Fix& fix, std::int64_t receive_ns);

  SampleRing<GpsRingEntry>* ring_;
  std::unique_ptr<nmea::SerialGpsReader> reader_;
  std::unique_ptr<recording::GpsStreamRecorder> recorder_;  // null: not recording
};

}  // namespace headingd::daemon
