#pragma once
// An NMEA log as the GPS source: drivers/nmea's NmeaLogPlayer feeds the log's sentences, at
// the pace of their UTC times, through the same epoch assembler and parser as the serial
// driver, on an Asio timer of the source's own thread. It is started when the log clock
// (playback_clock.hpp) reaches the log's first epoch, so it keeps step with a candump log
// recorded beside it.
//
// Sensor time: an epoch's t_ns is its UTC on the log clock (nmea_log_time.hpp), the axis of
// the candump log's timestamps, so the estimator places it among the IMU samples as it was
// recorded; arrival time: when the player fed it.
#include <atomic>
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "headingd/daemon/config.hpp"
#include "headingd/daemon/nmea_log_time.hpp"
#include "headingd/daemon/playback_clock.hpp"
#include "headingd/daemon/ring_entries.hpp"
#include "headingd/daemon/sample_ring.hpp"
#include "headingd/daemon/source.hpp"
#include "headingd/nmea/nmea_log_player.hpp"

namespace headingd::daemon {

class NmeaLogSource final : public Source {
 public:
  // Reads the whole log (throws std::runtime_error naming the file when it cannot).
  NmeaLogSource(std::string name, const NmeaLogSourceConfig& config, const PlaybackConfig& playback,
                const PlaybackClock* clock, std::uint16_t source_index, SampleRing<GpsRingEntry>* gps_ring);
  ~NmeaLogSource() override;

  const std::string& name() const override { return name_; }
  const char* kind() const override { return "nmea_log"; }
  void start() override;
  void stop() override;
  void report(SourceReport& out) const override;
  bool wantsExit() const override { return finished_.load() && at_end_ == AtEnd::kExit; }
  bool playing() const override { return !finished_.load(); }

  // The first epoch's time on the log clock, nullopt for a log without a time of fix.
  std::optional<std::int64_t> firstLogNs() const { return first_log_ns_; }
  std::size_t epochCount() const { return epochs_in_log_; }

 private:
  void onFix(const nmea::Fix& fix, std::int64_t receive_ns);
  void onFinished();
  void snapshotCounters();  // on the io thread (the player's counters live there)

  std::string name_;
  AtEnd at_end_;
  const PlaybackClock* clock_;
  std::uint16_t source_index_;
  SampleRing<GpsRingEntry>* ring_;
  std::optional<std::int64_t> first_log_ns_;
  std::int64_t first_day_ns_ = 0;
  std::int64_t offset_ns_ = 0;
  std::size_t epochs_in_log_ = 0;
  std::optional<NmeaLogTime> log_time_;  // made at start()

  boost::asio::io_context io_;
  std::unique_ptr<nmea::NmeaLogPlayer> player_;
  boost::asio::steady_timer start_timer_;
  boost::asio::steady_timer snapshot_timer_;
  std::thread thread_;
  std::atomic<bool> finished_{false};
  std::atomic<std::uint64_t> pushed_{0}, dropped_{0}, untimed_{0};
  mutable std::mutex snapshot_mutex_;
  nmea::NmeaLogPlayerCounters snapshot_;
};

}  // namespace headingd::daemon
