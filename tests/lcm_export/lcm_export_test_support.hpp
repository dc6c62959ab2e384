#pragma once
// Real LCM log files written by LCM's own writer (lcm::LogFile), the exporter run as a
// program, and headingd messages with a distinct, awkward value in every field.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "headingd/attitude_t.hpp"
#include "headingd/gps_t.hpp"
#include "headingd/heading_t.hpp"
#include "headingd/imu_t.hpp"
#include "headingd/status_t.hpp"

namespace headingd::lcm_export::test {

struct LoggedEvent {
  std::string channel;
  std::vector<std::uint8_t> data;
  std::int64_t utime = 0;
  std::int64_t event_number = -1;  // -1: its index in the log (writeLcmLog numbers them so)
};

// Every event of an LCM log, read with LCM's own reader.
inline std::vector<LoggedEvent> readLcmLog(const std::filesystem::path& path) {
  lcm::LogFile log(path.string(), "r");
  if (!log.good()) throw std::runtime_error(path.string() + ": cannot read");
  std::vector<LoggedEvent> events;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    const auto* bytes = static_cast<const std::uint8_t*>(e->data);
    events.push_back(LoggedEvent{e->channel, {bytes, bytes + e->datalen}, e->timestamp, e->eventnum});
  }
  return events;
}

template <class Message>
LoggedEvent eventOf(const std::string& channel, const Message& message, std::int64_t utime) {
  LoggedEvent e{channel, std::vector<std::uint8_t>(static_cast<std::size_t>(message.getEncodedSize())), utime};
  message.encode(e.data.data(), 0, static_cast<int>(e.data.size()));
  return e;
}

// Writes the events with LCM's log writer; returns each event's byte offset in the file
// (28-byte header, channel, data: LCM's eventlog format), and the file's size last.
inline std::vector<std::uint64_t> writeLcmLog(const std::filesystem::path& path,
                                              const std::vector<LoggedEvent>& events) {
  std::vector<std::uint64_t> offsets;
  std::uint64_t offset = 0;
  {
    lcm::LogFile log(path.string(), "w");
    if (!log.good()) throw std::runtime_error(path.string() + ": cannot write");
    for (std::size_t i = 0; i < events.size(); ++i) {
      lcm::LogEvent event;
      event.eventnum = static_cast<std::int64_t>(i);
      event.timestamp = events[i].utime;
      event.channel = events[i].channel;
      event.datalen = static_cast<std::int32_t>(events[i].data.size());
      event.data = const_cast<std::uint8_t*>(events[i].data.data());
      if (log.writeEvent(&event) != 0) throw std::runtime_error(path.string() + ": write failed");
      offsets.push_back(offset);
      offset += 28 + events[i].channel.size() + events[i].data.size();
    }
  }
  offsets.push_back(offset);
  EXPECT_EQ(std::filesystem::file_size(path), offset);
  return offsets;
}

struct RunResult {
  int status = -1;
  std::string out, err;
};

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline RunResult runExporter(const std::filesystem::path& work, const std::string& arguments) {
  const std::string command = std::string(HEADINGD_LCM_EXPORT_BIN) + " " + arguments + " >" +
                              (work / "stdout").string() + " 2>" + (work / "stderr").string();
  const int raw = std::system(command.c_str());
  RunResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = readText(work / "stdout");
  r.err = readText(work / "stderr");
  return r;
}

// A fresh folder per test, removed at the end.
class TempDir {
 public:
  TempDir() {
    char pattern[] = "/tmp/headingd-lcm-export-XXXXXX";
    if (mkdtemp(pattern) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Values that are hard to write and read back: extremes, -0, subnormals, NaN and infinities,
// text with separators, quotes, line breaks and non-ASCII bytes; between them values that
// differ from call to call, so that two fields swapped would show.
class AwkwardValues {
 public:
  explicit AwkwardValues(unsigned seed) : n_(seed) {}
  double real() {
    static const double pool[] = {0.1,
                                  -0.0,
                                  5e-324,
                                  1.7976931348623157e308,
                                  std::numeric_limits<double>::quiet_NaN(),
                                  std::numeric_limits<double>::infinity(),
                                  -std::numeric_limits<double>::infinity(),
                                  1.0 / 3.0,
                                  2.2250738585072014e-308};
    const unsigned k = n_++;
    return k % 3 == 0 ? pool[(k / 3) % std::size(pool)] : -2.718281828459045 * k + 1e-3;
  }
  std::int64_t i64() {
    static const std::int64_t pool[] = {std::numeric_limits<std::int64_t>::min(),
                                        std::numeric_limits<std::int64_t>::max(), 0};
    const unsigned k = n_++;
    return k % 3 == 0 ? pool[(k / 3) % std::size(pool)] : 1000000007LL * k - 3;
  }
  std::int32_t i32() {
    static const std::int32_t pool[] = {std::numeric_limits<std::int32_t>::min(),
                                        std::numeric_limits<std::int32_t>::max()};
    const unsigned k = n_++;
    return k % 3 == 0 ? pool[(k / 3) % std::size(pool)] : static_cast<std::int32_t>(1009 * k) - 5;
  }
  std::int8_t i8() {
    static const std::int8_t pool[] = {-128, 127, 0, 1, 2};
    return pool[n_++ % std::size(pool)];
  }
  std::string text() {
    static const char* pool[] = {"with,comma", "say \"hi\"",         "two\nlines", "",
                                 " spaced ",   "gr\xC3\xBC\xC3\x9F", "cr\rlf\r\n"};
    const unsigned k = n_++;
    return k % 2 == 0 ? std::string(pool[(k / 2) % std::size(pool)]) : "text " + std::to_string(k);
  }

  // Each argument (a field of a message, any of LCM's C++ types) gets the next value.
  template <class... Fields>
  void fill(Fields&... fields) {
    (fillOne(fields), ...);
  }

 private:
  void fillOne(double& x) { x = real(); }
  void fillOne(std::int64_t& x) { x = i64(); }
  void fillOne(std::int32_t& x) { x = i32(); }
  void fillOne(std::int8_t& x) { x = i8(); }
  void fillOne(std::string& x) { x = text(); }
  template <class T, std::size_t N>
  void fillOne(T (&array)[N]) {
    for (T& x : array) fillOne(x);
  }
  unsigned n_;
};

inline headingd::heading_t awkwardHeading(AwkwardValues& v) {
  headingd::heading_t m;
  v.fill(m.utime, m.sample_utime, m.sample_age_us, m.validity, m.heading_true_rad, m.heading_mag_rad,
         m.heading_mag_sigma_rad, m.heading_true_sigma_rad, m.declination_rad, m.declination_sigma_rad,
         m.declination_sources, m.declination_source, m.mount_yaw_rad, m.mount_yaw_sigma_rad, m.mag_disturbed,
         m.mag_norm_jump, m.mag_dip_jump, m.mag_norm_reference, m.mag_dip_reference, m.mag_used, m.mag_gain,
         m.mag_innovation_rad, m.heading_redefined);
  return m;
}

inline headingd::attitude_t awkwardAttitude(AwkwardValues& v) {
  headingd::attitude_t m;
  v.fill(m.utime, m.sample_utime, m.sample_age_us, m.validity, m.q_nb, m.roll_rad, m.pitch_rad, m.yaw_rad,
         m.q_covariance, m.motion_level, m.motion_level_name, m.accel_disturbance, m.at_rest, m.gyro_bias_rad_s,
         m.head_height);
  return m;
}

inline headingd::imu_t awkwardImu(AwkwardValues& v) {
  headingd::imu_t m;
  v.fill(m.utime, m.sample_utime, m.source, m.gyro_rad_s, m.accel_m_s2, m.has_mag, m.mag_uT, m.verdict, m.verdict_name);
  return m;
}

inline headingd::gps_t awkwardGps(AwkwardValues& v) {
  headingd::gps_t m;
  v.fill(m.utime, m.sample_utime, m.source, m.fix_ok, m.has_position, m.latitude_deg, m.longitude_deg, m.height_m,
         m.has_course, m.course_rad, m.has_speed, m.speed_mps, m.has_hdop, m.hdop, m.has_magvar, m.magvar_rad,
         m.decimal_year);
  return m;
}

inline headingd::counter_t counter(const std::string& name, std::int64_t value) {
  headingd::counter_t c;
  c.name = name;
  c.value = value;
  return c;
}

// `sources` names; each source gets `counters_per_source` counters. Estimator counters:
// named ones, plus a repeated and an empty name (keyed by index in the table).
inline headingd::status_t awkwardStatus(AwkwardValues& v, const std::vector<std::string>& sources,
                                        int counters_per_source, bool odd_counters) {
  headingd::status_t m;
  v.fill(m.utime, m.state, m.reason, m.uptime_us);
  for (const std::string& name : sources) {
    headingd::source_status_t s;
    s.name = name;
    v.fill(s.kind, s.state, s.last_error);
    for (int c = 0; c < counters_per_source; ++c) s.counters.push_back(counter("frames_" + std::to_string(c), v.i64()));
    s.num_counters = static_cast<std::int32_t>(s.counters.size());
    m.sources.push_back(s);
  }
  m.num_sources = static_cast<std::int32_t>(m.sources.size());
  headingd::ring_status_t ring;
  ring.name = "imu";
  v.fill(ring.capacity, ring.high_water, ring.window_high_water, ring.pushed, ring.dropped);
  m.rings = {ring};
  m.num_rings = 1;
  v.fill(m.rate_hz, m.ticks, m.deadline_misses, m.tick_jitter_p50_us, m.tick_jitter_p99_us, m.tick_jitter_max_us,
         m.processing_p50_us, m.processing_p99_us, m.processing_max_us, m.sample_age_p50_us, m.sample_age_p99_us,
         m.heading_rate_hz, m.imu_rate_hz, m.gps_rate_hz, m.publish_errors, m.estimator_policy, m.estimator_priority,
         m.driver_policy, m.driver_priority);
  m.memory_locked = v.i8() % 2 != 0;
  m.counters = {counter("gate_gap", v.i64()), counter("weird, \"name\"", v.i64())};
  if (odd_counters) {
    m.counters.push_back(counter("gate_gap", v.i64()));
    m.counters.push_back(counter("", v.i64()));
  }
  m.num_counters = static_cast<std::int32_t>(m.counters.size());
  return m;
}

}  // namespace headingd::lcm_export::test
