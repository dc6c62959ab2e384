#pragma once
// The serial GPS receiver as a source: drivers/nmea's SerialGpsReader on an io_context of
// its own thread; each completed epoch goes into the GPS ring, stamped with its monotonic
// receive time (the IMU's time axis for live sources).
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "headingd/daemon/ring_entries.hpp"
#include "headingd/daemon/sample_ring.hpp"
#include "headingd/daemon/source.hpp"
#include "headingd/nmea/serial_gps_reader.hpp"

namespace headingd::daemon {

class SerialGpsSource final : public Source {
 public:
  SerialGpsSource(std::string name, const nmea::SerialGpsConfig& config, std::uint16_t source_index,
                  SampleRing<GpsRingEntry>* gps_ring);
  ~SerialGpsSource() override;

  const std::string& name() const override { return name_; }
  const char* kind() const override { return "gps_serial"; }
  void start() override;
  void stop() override;
  void report(SourceReport& out) const override;

 private:
  void onFix(const nmea::Fix& fix, std::int64_t receive_ns);
  void snapshotCounters();  // on the io thread (the reader's counters live there)

  std::string name_;
  std::uint16_t source_index_;
  SampleRing<GpsRingEntry>* ring_;
  boost::asio::io_context io_;
  std::optional<boost::asio::executor_work_guard<boost::asio::io_context::executor_type>> work_;
  std::unique_ptr<nmea::SerialGpsReader> reader_;
  boost::asio::steady_timer snapshot_timer_;
  std::thread thread_;
  std::atomic<std::uint64_t> pushed_{0}, dropped_{0};
  mutable std::mutex snapshot_mutex_;
  nmea::SerialGpsCounters snapshot_;
};

}  // namespace headingd::daemon
