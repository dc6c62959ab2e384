#pragma once
// A real LCM subscriber on every headingd channel, decoding with the generated types and
// keeping each message with its CLOCK_MONOTONIC receive time.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <set>
#include <sstream>
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
    // Room for a BROAD trial's IMU messages and minutes of estimates: a vector that grows
    // copies everything it holds, and the handler falls behind meanwhile.
    heading_.reserve(1 << 14);
    attitude_.reserve(1 << 14);
    imu_.reserve(1 << 17);
    // LCM keeps at most 30 received messages a subscription by default and drops the rest
    // while the handler is behind: 10 ms of IMU messages at 10x real time. This subscriber
    // must see everything the daemon sent, so its queues are as deep as a whole trial.
    for (lcm::Subscription* s :
         {lcm_.subscribe("HEADING", &LcmCollector::onHeading, this),
          lcm_.subscribe("ATTITUDE", &LcmCollector::onAttitude, this),
          lcm_.subscribe("IMU", &LcmCollector::onImu, this), lcm_.subscribe("GPS", &LcmCollector::onGps, this),
          lcm_.subscribe("STATUS", &LcmCollector::onStatus, this)}) {
      s->setQueueCapacity(1 << 17);
    }
    thread_ = std::thread([this] {
      while (!stop_.load()) lcm_.handleTimeout(20);
    });
  }
  ~LcmCollector() { stop(); }
  void stop() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
  }

  // Datagrams the kernel dropped because a UDP socket of this process had a full receive
  // buffer (the "drops" column of /proc/self/net/udp for the sockets this process holds):
  // what this subscriber lost when it was not scheduled in time, as opposed to what the
  // daemon never sent.
  static std::uint64_t kernelReceiveDrops() {
    std::set<std::string> inodes;
    for (const auto& fd : std::filesystem::directory_iterator("/proc/self/fd")) {
      std::error_code ec;
      const std::string target = std::filesystem::read_symlink(fd.path(), ec).string();
      if (!ec && target.rfind("socket:[", 0) == 0) inodes.insert(target.substr(8, target.size() - 9));
    }
    std::ifstream udp("/proc/self/net/udp");
    std::string line;
    std::getline(udp, line);  // header
    std::uint64_t drops = 0;
    while (std::getline(udp, line)) {
      std::istringstream fields(line);
      std::vector<std::string> f;
      for (std::string x; fields >> x;) f.push_back(x);
      // sl local rem st tx:rx tr:when retrnsmt uid timeout inode ref pointer drops
      if (f.size() >= 13 && inodes.count(f[9]) != 0) drops += std::stoull(f[12]);
    }
    return drops;
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
