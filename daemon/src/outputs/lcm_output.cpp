#include "headingd/daemon/outputs/lcm_output.hpp"

namespace headingd::daemon {

void LcmOutput::imuSample(const ImuRingEntry& entry, core::SampleVerdict verdict, const std::string& source_name,
                          std::int64_t utime_us) {
  if (!config_.publish_imu) return;
  fillImu(imu_msg_, entry.sample, verdict, source_name, utime_us);
  if (publisher_.publish(config_.imu_channel, imu_msg_)) ++published_.imu;
}

void LcmOutput::gpsEpoch(const GpsRingEntry& entry, std::uint64_t /*imu_samples_before*/,
                         const std::string& source_name, std::int64_t utime_us) {
  if (!config_.publish_gps) return;
  fillGps(gps_msg_, entry.observation, source_name, utime_us);
  if (publisher_.publish(config_.gps_channel, gps_msg_)) ++published_.gps;
}

void LcmOutput::estimate(const PublishedEstimate& e) {
  const core::HeadingOutput& out = e.pipeline.output();
  fillHeading(heading_msg_, out, e.validity, e.times);
  fillAttitude(attitude_msg_, out, e.pipeline.estimator().ekf().covariance(), e.validity, e.times);
  // The sample's age is measured when HEADING has been sent, by the sender thread.
  const bool heading_ok =
      publisher_.publish(config_.heading_channel, heading_msg_, e.fresh_arrival_ns.value_or(LcmPublisher::kNoSample));
  const bool attitude_ok = publisher_.publish(config_.attitude_channel, attitude_msg_);
  if (heading_ok && attitude_ok) ++published_.heading;
}

void LcmOutput::publishStatus(const status_t& m) {
  if (publisher_.publish(config_.status_channel, m)) ++published_.status;
}

}  // namespace headingd::daemon
