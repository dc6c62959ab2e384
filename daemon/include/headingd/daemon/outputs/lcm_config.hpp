#pragma once
// [lcm]: where the messages go and which of them (config.cpp reads the table).
#include <cstddef>
#include <string>

namespace headingd::daemon {

// The queue between the estimator thread and the LCM sender thread, by default (bytes):
// LcmPublisher::kDefaultQueueBytes (daemon.cpp checks that they agree).
inline constexpr std::size_t kDefaultSendQueueBytes = 1 << 20;

struct LcmConfig {
  std::string url = "udpm://239.255.76.67:7667?ttl=0";
  std::string heading_channel = "HEADING";
  std::string attitude_channel = "ATTITUDE";
  std::string imu_channel = "IMU";
  std::string gps_channel = "GPS";
  std::string status_channel = "STATUS";
  bool publish_imu = true;
  bool publish_gps = true;
  // The queue between the estimator thread and the LCM sender thread (bytes): what does not
  // fit while the sender is behind is not published, and counted (lcm_publisher.hpp).
  std::size_t send_queue_bytes = kDefaultSendQueueBytes;
};

}  // namespace headingd::daemon
