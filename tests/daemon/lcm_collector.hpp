#pragma once
// A real LCM subscriber on every headingd channel, decoding with the generated types and
// keeping each message with its CLOCK_MONOTONIC receive time.
#include <atomic>
#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "headingd/attitude_t.hpp"
#include "headingd/gps_t.hpp"
#include "headingd/heading_t.hpp"
#include "headingd/imu_t.hpp"
#include "headingd/status_t.hpp"

namespace headingd::daemon::test {

template <class Message>
struct Received {
  Message message;
  double receive_s = 0.0;  // steady clock
};

class LcmCollector {
 public:
  explicit LcmCollector(const std::string& url) : lcm_(url) {
    if (!lcm_.good()) throw std::runtime_error("LCM subscriber: cannot open " + url);
    lcm_.subscribe("HEADING", &LcmCollector::onHeading, this);
    lcm_.subscribe("ATTITUDE", &LcmCollector::onAttitude, this);
    lcm_.subscribe("IMU", &LcmCollector::onImu, this);
    lcm_.subscribe("GPS", &LcmCollector::onGps, this);
    lcm_.subscribe("STATUS", &LcmCollector::onStatus, this);
    thread_ = std::thread([this] {
      while (!stop_.load()) lcm_.handleTimeout(20);
    });
  }
  ~LcmCollector() { stop(); }
  void stop() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
  }

  // Copies, safe while receiving.
  std::vector<Received<headingd::heading_t>> heading() const { return copy(heading_); }
  std::vector<Received<headingd::attitude_t>> attitude() const { return copy(attitude_); }
  std::vector<Received<headingd::imu_t>> imu() const { return copy(imu_); }
  std::vector<Received<headingd::gps_t>> gps() const { return copy(gps_); }
  std::vector<Received<headingd::status_t>> status() const { return copy(status_); }

 private:
  static double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }
  template <class M>
  std::vector<Received<M>> copy(const std::vector<Received<M>>& v) const {
    std::lock_guard lock(mutex_);
    return v;
  }
  template <class M>
  void add(std::vector<Received<M>>& v, const M* m) {
    std::lock_guard lock(mutex_);
    v.push_back({*m, now()});
  }
  void onHeading(const lcm::ReceiveBuffer*, const std::string&, const headingd::heading_t* m) { add(heading_, m); }
  void onAttitude(const lcm::ReceiveBuffer*, const std::string&, const headingd::attitude_t* m) { add(attitude_, m); }
  void onImu(const lcm::ReceiveBuffer*, const std::string&, const headingd::imu_t* m) { add(imu_, m); }
  void onGps(const lcm::ReceiveBuffer*, const std::string&, const headingd::gps_t* m) { add(gps_, m); }
  void onStatus(const lcm::ReceiveBuffer*, const std::string&, const headingd::status_t* m) { add(status_, m); }

  lcm::LCM lcm_;
  mutable std::mutex mutex_;
  std::vector<Received<headingd::heading_t>> heading_;
  std::vector<Received<headingd::attitude_t>> attitude_;
  std::vector<Received<headingd::imu_t>> imu_;
  std::vector<Received<headingd::gps_t>> gps_;
  std::vector<Received<headingd::status_t>> status_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace headingd::daemon::test
