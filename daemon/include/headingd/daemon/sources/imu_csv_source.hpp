#pragma once
// A file source: an IMU CSV (BROAD format) and optionally an NMEA capture on the same time
// axis (drivers/files), played into the rings at real-time pace times `speed`. The files
// are read completely at construction (errors stop start-up); playing allocates nothing.
//
// Samples keep the file's time column as their sensor time (so the estimator sees exactly
// what headingd-replay sees); their arrival time is the monotonic time they were pushed.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/loop/sample_ring.hpp"
#include "headingd/daemon/sources/source.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/nmea/counters.hpp"

namespace headingd::daemon {

// [imu_csv]
struct ImuCsvSourceConfig : SourceConfig {
  std::string imu_csv_path;  // BROAD format, plain or gzip (drivers/files imu_csv.hpp)
  std::string nmea_path;     // optional GPS capture on the IMU time axis ("" = none)
  double nmea_first_epoch_t_s = 0.0;
  double speed = 1.0;  // play speed, 1 = real time
  double start_delay_s = 0.0;
  AtEnd at_end = AtEnd::kStay;
  // false: samples keep the file's own time column (what headingd-replay sees, any speed).
  // true: the file's times moved by one constant onto CLOCK_MONOTONIC (speed 1 only), the
  // axis of the live sources, so a recording can run beside a live GPS ([gps]).
  bool monotonic_time = false;
  bool no_mag = false;  // read no magnetometer (files::MagColumns::kIgnored)

  bool onMonotonicClock() const override { return monotonic_time; }
  std::unique_ptr<Source> createSource(SourceContext& context) const override;
};
std::unique_ptr<SourceConfig> parseImuCsvSource(const SourceTable& table);

class ImuCsvSource final : public Source {
 public:
  // `gps_ring` may be null when the configuration has no NMEA file. Throws
  // files::CsvError (or core::ConfigError) when a file cannot be read.
  ImuCsvSource(std::string name, const ImuCsvSourceConfig& config, std::uint16_t source_index,
               SampleRing<ImuRingEntry>* imu_ring, SampleRing<GpsRingEntry>* gps_ring);
  ~ImuCsvSource() override;

  const std::string& name() const override { return name_; }
  const char* kind() const override { return "imu_csv"; }
  bool readsAtRealTimePace() const override { return config_.speed <= 1.0; }
  void start() override;
  void stop() override;
  void report(SourceReport& out) const override;
  bool playing() const override { return state_.load() != SourceState::kFinished; }
  bool wantsExit() const override { return wants_exit_.load(); }

  std::size_t imuSampleCount() const { return imu_.size(); }
  std::size_t gpsEpochCount() const { return gps_.size(); }

 private:
  void run();
  // Sleeps until `mono_ns` or a stop request; false when asked to stop.
  bool sleepUntil(std::int64_t mono_ns);

  std::string name_;
  ImuCsvSourceConfig config_;
  std::uint16_t source_index_;
  SampleRing<ImuRingEntry>* imu_ring_;
  SampleRing<GpsRingEntry>* gps_ring_;
  std::vector<core::ImuSample> imu_;
  std::vector<core::GpsObservation> gps_;
  nmea::Counters nmea_counters_;
  std::int64_t loop_length_ns_ = 0;  // added to the times of each further loop

  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_requested_ = false;  // under mutex_
  std::atomic<SourceState> state_{SourceState::kStarting};
  std::atomic<bool> wants_exit_{false};
  std::atomic<std::uint64_t> imu_pushed_{0}, imu_dropped_{0}, gps_pushed_{0}, gps_dropped_{0}, loops_{0};
};

}  // namespace headingd::daemon
