#include "headingd/daemon/sources/nmea_log_source.hpp"

#include <spdlog/spdlog.h>
#include <chrono>
#include <cmath>
#include <vector>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/daemon/sources/median_step.hpp"
#include "headingd/daemon/sources/readable_path.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/input_file.hpp"
#include "headingd/files/nmea_epochs.hpp"
#include "headingd/nmea/gps_observation_from_fix.hpp"

namespace headingd::daemon {
namespace {

// How often the player's counters are copied for STATUS.
constexpr auto kSnapshotPeriod = std::chrono::milliseconds(250);

std::chrono::steady_clock::time_point steadyAt(std::int64_t mono_ns) {
  return std::chrono::steady_clock::time_point(std::chrono::nanoseconds(mono_ns));
}

}  // namespace

std::unique_ptr<SourceConfig> parseNmeaLogSource(const SourceTable& table) {
  auto c = std::make_unique<NmeaLogSourceConfig>();
  core::TomlTableReader nmea_log(&table.table, table.source, "nmea_log");
  c->enabled = nmea_log.boolean("enabled", false);
  c->path = readablePath(nmea_log, "path", "", table.base_dir, c->enabled, files::kWholeLogLimit);
  if (c->enabled && c->path.empty()) nmea_log.fail("path", "expected the NMEA log to play (the source is enabled)");
  c->time_offset_s = nmea_log.number("time_offset_s", 0.0, -1e9, 1e9, "s");
  nmea_log.rejectUnknownKeys();
  return c;
}

std::unique_ptr<Source> NmeaLogSourceConfig::createSource(SourceContext& context) const {
  const auto& c = *this;
  auto source = std::make_unique<NmeaLogSource>(c.table, c, context.playback, context.playback_clock,
                                                context.source_index, context.addGpsRing(c.table));
  spdlog::info("source nmea_log: {} ({} epochs)", c.path, source->epochCount());
  context.logStartsAt(source->firstLogNs());
  context.logEndsAt(source->lastLogNs(), source->epochStepNs());
  return source;
}

NmeaLogSource::NmeaLogSource(std::string name, const NmeaLogSourceConfig& config, const PlaybackConfig& playback,
                             const PlaybackClock* clock, std::uint16_t source_index, SampleRing<GpsRingEntry>* gps_ring)
    : AsioSource(std::move(name), source_index, Lifetime::kUntilPlayed, kSnapshotPeriod),
      at_end_(playback.at_end),
      clock_(clock),
      ring_(gps_ring),
      offset_ns_(std::llround(config.time_offset_s * 1e9)),
      start_timer_(io()) {
  // Read once, for the player and for the first epoch below. A gzip log cut short (a power
  // loss while recording) is played as far as it goes, and said so.
  files::MaybeCutText log = files::readMaybeGzipLog(config.path, files::kWholeLogLimit);
  end_missing_ = log.end_missing;
  if (end_missing_) {
    spdlog::warn(
        "{}: the gzip log is cut short: {} bytes of text read; the end of the log is missing, what was "
        "read is played",
        config.path, log.text.size());
  }
  const std::vector<nmea::FixUpdate> updates = files::parseNmeaLogFixes(log.text).updates;
  nmea::NmeaLogPlayerConfig player;
  player.path = config.path;
  player.contents = std::move(log.text);
  player.speed = playback.speed;
  // Gaps in the log (no fix indoors) are played as they are: shortened, they would put the
  // player ahead of the candump log it was recorded beside.
  player.max_gap_s = 86400.0;
  player_ = std::make_unique<nmea::NmeaLogPlayer>(
      io(), player, [this](const nmea::Fix& fix, std::int64_t receive_ns) { onFix(fix, receive_ns); },
      nmea::LineHandler{}, [this] { onFinished(); });

  // The first epoch's time and the log's first day, from the parser's view of the whole log.
  first_day_ns_ = NmeaLogTime::logDayStart(updates);
  std::optional<std::int64_t> previous_tod;
  for (const nmea::FixUpdate& u : updates) {
    if (u.fix.time_of_day_ns && u.fix.time_of_day_ns != previous_tod) {
      ++epochs_in_log_;
      previous_tod = u.fix.time_of_day_ns;
    }
  }
  // The first and last epoch times, and the usual step between epochs, as the player will
  // place them (one NmeaLogTime through the whole log: days roll over as they will).
  NmeaLogTime log_time(offset_ns_, first_day_ns_);
  std::vector<std::int64_t> steps;
  for (const nmea::FixUpdate& u : updates) {
    const std::optional<std::int64_t> t = log_time.of(u.fix);
    if (!t) continue;
    if (!first_log_ns_) first_log_ns_ = t;
    if (last_log_ns_ && *t > *last_log_ns_ && steps.size() < 1000) steps.push_back(*t - *last_log_ns_);
    if (!last_log_ns_ || *t > *last_log_ns_) last_log_ns_ = t;
  }
  epoch_step_ns_ = medianStep(std::move(steps));
}

NmeaLogSource::~NmeaLogSource() { stop(); }

void NmeaLogSource::onFix(const nmea::Fix& fix, std::int64_t receive_ns) {
  std::optional<std::int64_t> t = log_time_->of(fix);
  if (!t) {
    // No time of fix: placed where the log clock stands now.
    untimed_.fetch_add(1, std::memory_order_relaxed);
    t = clock_->logNsAt(receive_ns);
  } else {
    *t += loop_offset_ns_;
  }
  dates_not_believed_.store(dates_not_believed_in_past_loops_ + log_time_->datesNotBelieved(),
                            std::memory_order_relaxed);
  GpsRingEntry e;
  e.observation = nmea::gpsObservationFromFix(fix, *t);
  e.arrival_mono_ns = receive_ns;
  push(*ring_, e);
}

void NmeaLogSource::onFinished() {
  if (clock_->loop_ns > 0 && first_log_ns_) {  // loop_ns > 0: at_end = "loop"
    // Called from the player's last group: the next loop starts from the io thread's queue.
    dates_not_believed_in_past_loops_ += log_time_->datesNotBelieved();
    loop_offset_ns_ += clock_->loop_ns;
    loops_played_.fetch_add(1, std::memory_order_relaxed);
    startPlayerOnTime();
    return;
  }
  stopTicks();
  takeSnapshot();
  finished_.store(true);
}

void NmeaLogSource::onStart() { startPlayerOnTime(); }

void NmeaLogSource::startPlayerOnTime() {
  log_time_.emplace(offset_ns_, first_day_ns_);  // each loop places its epochs afresh
  // The player feeds its first group at once: start it when the log clock reaches it.
  const std::int64_t due = first_log_ns_ ? clock_->dueMonoNs(*first_log_ns_ + loop_offset_ns_) : clock_->start_mono_ns;
  start_timer_.expires_at(steadyAt(due));
  start_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) player_->start();
  });
}

void NmeaLogSource::report(SourceReport& out) const {
  out.state = finished_.load() ? SourceState::kFinished : SourceState::kRunning;
  out.last_error.clear();
  withSnapshot([&](const nmea::NmeaLogPlayerCounters& c) {
    std::size_t i = 0;
    out.set(i++, "epochs_in_log", epochs_in_log_);
    out.set(i++, "log_end_missing", end_missing_ ? 1u : 0u);
    out.set(i++, "epochs", c.epochs.epochs);
    out.set(i++, "epochs_pushed", pushed());
    out.set(i++, "ring_full_drops", ringFullDrops());
    out.set(i++, "epochs_without_time", untimed_.load(std::memory_order_relaxed));
    out.set(i++, "dates_not_believed", dates_not_believed_.load(std::memory_order_relaxed));
    out.set(i++, "late_sentences", c.epochs.late_sentences);
    out.set(i++, "groups_played", c.groups_played);
    out.set(i++, "loops_played", loops_played_.load(std::memory_order_relaxed));
    out.set(i++, "backward_steps", c.backward_steps);
    nmea::forEachCounter(c.parser, [&](const char* name, std::uint64_t v) { out.set(i++, "nmea_", name, v); });
  });
}

}  // namespace headingd::daemon
