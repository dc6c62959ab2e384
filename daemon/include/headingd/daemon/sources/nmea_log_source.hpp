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
//
// [playback] at_end = "loop": once played, the log starts again when the log clock reaches
// its first epoch one loop later (playback_clock.hpp), every epoch's time moved on by the
// loop length; loops_played on STATUS.
#include <atomic>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <memory>
#include <optional>

#include "headingd/daemon/loop/ring_entries.hpp"
#include "headingd/daemon/sources/asio_source.hpp"
#include "headingd/daemon/sources/nmea_log_time.hpp"
#include "headingd/daemon/sources/playback_clock.hpp"
#include "headingd/daemon/sources/source_registry.hpp"
#include "headingd/nmea/nmea_log_player.hpp"

namespace headingd::daemon {

// [nmea_log]: an NMEA 0183 log (plain or gzip) played by drivers/nmea's NmeaLogPlayer. A gzip
// log cut short is played as far as it goes (log_end_missing on STATUS).
struct NmeaLogSourceConfig : SourceConfig {
  std::string path;
  // Added to the sentences' UTC to put the epochs on the candump log's clock (a recorder
  // whose wall clock was off by this much).
  double time_offset_s = 0.0;
  std::unique_ptr<Source> createSource(SourceContext& context) const override;
};
std::unique_ptr<SourceConfig> parseNmeaLogSource(const SourceTable& table);

class NmeaLogSource final : public AsioSource<nmea::NmeaLogPlayerCounters> {
 public:
  // Reads the whole log (throws files::FileError naming the file when it cannot, or when its
  // gzip stream is corrupt).
  NmeaLogSource(std::string name, const NmeaLogSourceConfig& config, const PlaybackConfig& playback,
                const PlaybackClock* clock, std::uint16_t source_index, SampleRing<GpsRingEntry>* gps_ring);
  ~NmeaLogSource() override;

  const char* kind() const override { return "nmea_log"; }
  bool readsAtRealTimePace() const override { return clock_->speed <= 1.0; }
  void report(SourceReport& out) const override;
  bool wantsExit() const override { return finished_.load() && at_end_ == AtEnd::kExit; }
  bool playing() const override { return !finished_.load(); }

  // The first epoch's time on the log clock, nullopt for a log without a time of fix.
  std::optional<std::int64_t> firstLogNs() const { return first_log_ns_; }
  std::optional<std::int64_t> lastLogNs() const { return last_log_ns_; }
  // The usual step between two epochs (median), nullopt for fewer than two.
  std::optional<std::int64_t> epochStepNs() const { return epoch_step_ns_; }
  std::size_t epochCount() const { return epochs_in_log_; }

 private:
  void onStart() override;  // the player starts when the log clock reaches the first epoch
  nmea::NmeaLogPlayerCounters currentCounters() const override { return player_->counters(); }
  void onFix(const nmea::Fix& fix, std::int64_t receive_ns);
  void onFinished();
  // Starts the player when the log clock reaches the first epoch of the current loop.
  void startPlayerOnTime();

  AtEnd at_end_;
  const PlaybackClock* clock_;
  SampleRing<GpsRingEntry>* ring_;
  std::optional<std::int64_t> first_log_ns_;
  std::optional<std::int64_t> last_log_ns_;
  std::optional<std::int64_t> epoch_step_ns_;
  std::int64_t loop_offset_ns_ = 0;  // added to every epoch time of the loop being played
  std::uint64_t dates_not_believed_in_past_loops_ = 0;
  std::optional<std::int64_t> first_day_ns_;  // NmeaLogTime::logDayStart
  std::int64_t offset_ns_ = 0;
  std::size_t epochs_in_log_ = 0;
  bool end_missing_ = false;             // the gzip stream ended before its trailer
  std::optional<NmeaLogTime> log_time_;  // made at start()

  std::unique_ptr<nmea::NmeaLogPlayer> player_;
  boost::asio::steady_timer start_timer_;
  std::atomic<bool> finished_{false};
  std::atomic<std::uint64_t> untimed_{0};
  std::atomic<std::uint64_t> dates_not_believed_{0};  // NmeaLogTime::datesNotBelieved, for STATUS
  std::atomic<std::uint64_t> loops_played_{0};
};

}  // namespace headingd::daemon
