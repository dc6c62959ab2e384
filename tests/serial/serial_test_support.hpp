#pragma once
// Helpers for the serial driver tests: an io_context on its own thread, the reference
// epochs of the pure parser, and Fix values written out exactly for comparison.
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>

#include <chrono>
#include <cstdio>
#include <functional>
#include <future>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "headingd/nmea/fix.hpp"
#include "headingd/nmea/parser.hpp"

namespace headingd::test {

// Every field at round-trip precision (%.17g): two Fix values are equal bit for bit iff
// their texts are.
inline std::string fixText(const nmea::Fix& f) {
  std::string s;
  auto num = [&](const char* name, const auto& v) {
    char b[64];
    if (!v) {
      std::snprintf(b, sizeof b, "%s=- ", name);
    } else {
      std::snprintf(b, sizeof b, "%s=%.17g ", name, static_cast<double>(*v));
    }
    s += b;
  };
  num("tod", f.time_of_day_ns);
  num("utc", f.utc_ns);
  if (f.position) {
    num("lat", std::optional<double>(f.position->lat_deg));
    num("lon", std::optional<double>(f.position->lon_deg));
  } else {
    s += "pos=- ";
  }
  num("alt", f.alt_msl_m);
  num("sep", f.geoid_separation_m);
  num("cog", f.course_deg);
  num("sog", f.speed_mps);
  s += std::string("mode=") + (f.mode ? nmea::fixModeName(*f.mode) : "-") + " ";
  num("q", f.quality);
  num("hdop", f.hdop);
  num("pdop", f.pdop);
  num("vdop", f.vdop);
  num("sats", f.satellites_used);
  num("magvar", f.magvar_deg);
  num("hdt", f.heading_deg);
  num("slat", f.lat_sigma_m);
  num("slon", f.lon_sigma_m);
  num("salt", f.alt_sigma_m);
  return s;
}

// The epochs of the pure parser on the same bytes, by replay's rule (nmea_epochs.cpp): the
// Fix after the last sentence of each UTC time of day.
inline std::vector<std::string> referenceEpochs(std::span<const std::uint8_t> bytes,
                                                nmea::Counters* counters = nullptr) {
  nmea::Parser parser;
  std::vector<nmea::FixUpdate> updates;
  parser.feed(bytes, updates);
  std::vector<std::string> epochs;
  for (std::size_t i = 0; i < updates.size(); ++i) {
    const auto& tod = updates[i].fix.time_of_day_ns;
    if (!tod) continue;
    if (i + 1 == updates.size() || updates[i + 1].fix.time_of_day_ns != tod) epochs.push_back(fixText(updates[i].fix));
  }
  if (counters) *counters = parser.counters();
  return epochs;
}

inline std::vector<std::pair<std::string, std::uint64_t>> counterList(const nmea::Counters& c) {
  std::vector<std::pair<std::string, std::uint64_t>> v;
  nmea::forEachCounter(c, [&](const char* name, std::uint64_t value) { v.emplace_back(name, value); });
  return v;
}

// An io_context run by its own thread for the life of this object.
class IoThread {
 public:
  IoThread() : work_(io_.get_executor()), thread_([this] { io_.run(); }) {}
  ~IoThread() { stopAndJoin(); }
  boost::asio::io_context& io() { return io_; }

  // Runs fn on the io thread and returns its result (the driver's state lives there).
  template <class Fn>
  auto call(Fn fn) -> decltype(fn()) {
    std::packaged_task<decltype(fn())()> task(std::move(fn));
    auto result = task.get_future();
    boost::asio::post(io_, [&task] { task(); });
    return result.get();
  }

  void stopAndJoin() {
    work_.reset();
    io_.stop();
    if (thread_.joinable()) thread_.join();
  }

 private:
  boost::asio::io_context io_;
  boost::asio::executor_work_guard<boost::asio::io_context::executor_type> work_;
  std::thread thread_;
};

// Polls pred every 10 ms until it holds or timeout passes; returns whether it held.
inline bool waitFor(const std::function<bool()>& pred, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!pred()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

inline std::int64_t monotonicNs() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace headingd::test
