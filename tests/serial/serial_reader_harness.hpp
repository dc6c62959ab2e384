#pragma once
// A SerialGpsReader on its own io thread for the serial driver's tests, with what it handed
// out collected, the reader settings the tests use (short back-off), and comparisons.
#include <gtest/gtest.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "headingd/nmea/serial_gps_reader.hpp"
#include "serial_test_support.hpp"

namespace headingd::test {

// What the reader handed out, collected from the io thread.
struct Received {
  std::mutex mutex;
  std::vector<std::string> fixes;
  std::vector<std::int64_t> receive_ns;
  std::vector<std::int64_t> delivered_ns;
  std::size_t lines = 0;

  std::size_t fixCount() {
    std::lock_guard lock(mutex);
    return fixes.size();
  }
  std::vector<std::string> fixesCopy() {
    std::lock_guard lock(mutex);
    return fixes;
  }
};

// The reader on its own io thread; destroyed on that thread before the thread stops.
class Harness {
 public:
  explicit Harness(nmea::SerialGpsConfig config) {
    reader_ = std::make_unique<nmea::SerialGpsReader>(
        io_.io(), std::move(config),
        [this](const nmea::Fix& fix, std::int64_t receive_ns) {
          std::lock_guard lock(received.mutex);
          received.fixes.push_back(fixText(fix));
          received.receive_ns.push_back(receive_ns);
          received.delivered_ns.push_back(monotonicNs());
        },
        [this](std::string_view, std::int64_t) {
          std::lock_guard lock(received.mutex);
          ++received.lines;
        });
    io_.call([this] { reader_->start(); });
  }
  ~Harness() {
    io_.call([this] { reader_.reset(); });
    io_.stopAndJoin();
  }

  nmea::SerialGpsCounters counters() {
    return io_.call([this] { return reader_->counters(); });
  }
  void stop() {
    io_.call([this] { reader_->stop(); });
  }
  bool waitState(nmea::SerialGpsState s, std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    return waitFor([&] { return counters().state == s; }, timeout);
  }
  bool waitBytes(std::uint64_t n, std::chrono::milliseconds timeout = std::chrono::milliseconds(10000)) {
    return waitFor([&] { return counters().parser.framing.bytes >= n; }, timeout);
  }

  Received received;

 private:
  IoThread io_;
  std::unique_ptr<nmea::SerialGpsReader> reader_;
};

inline nmea::SerialGpsConfig testConfig(const std::string& device) {
  nmea::SerialGpsConfig c;
  c.device = device;
  c.baud = 115200;
  c.reopen_backoff_initial_s = 0.05;
  c.reopen_backoff_max_s = 0.2;
  // Long enough that a writer thread descheduled on a busy machine does not cut an epoch
  // in two; the last epoch of a capture arrives this long after its last byte.
  c.epoch_idle_s = 0.5;
  c.path_check_s = 0.1;
  return c;
}

inline void expectCountersEqual(const nmea::Counters& got, const nmea::Counters& want) {
  const auto g = counterList(got);
  const auto w = counterList(want);
  ASSERT_EQ(g.size(), w.size());
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_EQ(g[i].second, w[i].second) << g[i].first;
}

inline void expectSameFixes(const std::vector<std::string>& got, const std::vector<std::string>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], want[i]) << "epoch " << i;
}

}  // namespace headingd::test
