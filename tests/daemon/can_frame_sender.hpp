#pragma once
// A CAN bus sender for the fault tests: plays the frames of a candump log onto an interface
// through a raw CAN socket, in a loop, either paced by the log's own times (real time) or as
// fast as the socket takes them (a flood). Unlike canplayer it survives the interface going
// down: a failed write is counted, the socket is opened again 20 ms later and play goes on.
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "headingd/can/candump_log.hpp"

namespace headingd::daemon::test {

class CanFrameSender {
 public:
  struct Timed {
    can_frame frame;
    std::int64_t t_ns;  // the log's time
  };

  CanFrameSender(const std::string& candump_log, std::string interface) : interface_(std::move(interface)) {
    std::ifstream in(candump_log);
    std::string line;
    while (std::getline(in, line)) {
      const auto logged = can::parseCandumpLine(line);
      if (!logged) continue;
      Timed t{};
      const can::CanFrame& f = logged->frame;
      t.frame.can_id = f.extended ? (f.id | CAN_EFF_FLAG) : f.id;
      t.frame.len = f.len;
      std::memcpy(t.frame.data, f.data.data(), f.len);
      t.t_ns = f.t_ns;
      frames_.push_back(t);
    }
    if (frames_.empty()) throw std::runtime_error("no frames in " + candump_log);
  }
  ~CanFrameSender() { stop(); }

  void start() {
    thread_ = std::thread([this] { run(); });
  }
  void stop() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
  }
  // Flood (true) or play at the log's pace (false); changes take effect within one frame.
  void setFlood(bool flood) { flood_.store(flood); }

  std::uint64_t sent() const { return sent_.load(); }               // frames the socket took
  std::uint64_t sendErrors() const { return send_errors_.load(); }  // writes refused (interface down)

 private:
  int openSocket() {
    const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (fd < 0) return -1;
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = static_cast<int>(if_nametoindex(interface_.c_str()));
    if (addr.can_ifindex == 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
      ::close(fd);
      return -1;
    }
    return fd;
  }

  void run() {
    using Clock = std::chrono::steady_clock;
    int fd = openSocket();
    std::size_t i = 0;
    // Paced: frame i is due at anchor + (t_i - anchor_t); re-anchored after a flood and at
    // each new loop of the log.
    Clock::time_point anchor = Clock::now();
    std::int64_t anchor_t = frames_[0].t_ns;
    bool was_flood = false, reanchor = false;
    while (!stop_.load()) {
      const Timed& f = frames_[i];
      const bool flood = flood_.load();
      if (i == 0 || reanchor || (was_flood && !flood)) {
        reanchor = false;
        anchor = Clock::now();
        anchor_t = f.t_ns;
      }
      was_flood = flood;
      if (!flood) std::this_thread::sleep_until(anchor + std::chrono::nanoseconds(f.t_ns - anchor_t));
      if (fd >= 0 && ::write(fd, &f.frame, sizeof f.frame) == static_cast<ssize_t>(sizeof f.frame)) {
        sent_.fetch_add(1);
      } else {
        send_errors_.fetch_add(1);
        if (fd >= 0) ::close(fd);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        fd = openSocket();
        reanchor = true;  // no catching up afterwards: a bus that was down lost those frames
      }
      i = (i + 1) % frames_.size();
    }
    if (fd >= 0) ::close(fd);
  }

  std::string interface_;
  std::vector<Timed> frames_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, flood_{false};
  std::atomic<std::uint64_t> sent_{0}, send_errors_{0};
};

}  // namespace headingd::daemon::test
