#pragma once
// LCM as an estimate sink: IMU and GPS as each went into the estimator ([lcm] publish_imu,
// publish_gps), HEADING and ATTITUDE for each estimate, and STATUS when the loop has filled it.
// Encodes into the publisher's queue; the LCM sender thread sends (lcm_publisher.hpp).
#include "headingd/attitude_t.hpp"
#include "headingd/daemon/outputs/estimate_sink.hpp"
#include "headingd/daemon/outputs/lcm_config.hpp"
#include "headingd/daemon/outputs/lcm_publisher.hpp"
#include "headingd/gps_t.hpp"
#include "headingd/heading_t.hpp"
#include "headingd/imu_t.hpp"

namespace headingd::daemon {

// Messages handed to the LCM sender so far; STATUS's rates are the differences between two STATUS.
struct PublishedCounts {
  std::uint64_t heading = 0, imu = 0, gps = 0, status = 0;
};

class LcmOutput final : public EstimateSink {
 public:
  // Both borrowed; they must outlive the output.
  LcmOutput(const LcmConfig& config, LcmPublisher& publisher) : config_(config), publisher_(publisher) {}

  void imuSample(const ImuRingEntry& entry, core::SampleVerdict verdict, const std::string& source_name,
                 std::int64_t utime_us) override;
  void gpsEpoch(const GpsRingEntry& entry, std::uint64_t imu_samples_before, const std::string& source_name,
                std::int64_t utime_us) override;
  void estimate(const PublishedEstimate& estimate) override;
  void publishStatus(const status_t& m);

  // Messages handed to the sender so far (HEADING counts when ATTITUDE went too), for STATUS's rates.
  const PublishedCounts& published() const { return published_; }

 private:
  const LcmConfig& config_;
  LcmPublisher& publisher_;
  PublishedCounts published_;
  // Reused messages (no allocation per sample once their strings have grown).
  headingd::heading_t heading_msg_{};
  headingd::attitude_t attitude_msg_{};
  headingd::imu_t imu_msg_{};
  headingd::gps_t gps_msg_{};
};

}  // namespace headingd::daemon
