#include "headingd/daemon/sources/recording_source.hpp"

#include <spdlog/spdlog.h>
#include <chrono>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/live/clocks.hpp"

namespace headingd::daemon {
namespace {

// How often the reader's counters are copied for STATUS.
constexpr auto kSnapshotPeriod = std::chrono::milliseconds(250);
// A full ring is retried after this long (the estimator drains it every tick).
constexpr std::int64_t kRingFullRetryNs = 2'000'000;

}  // namespace

std::unique_ptr<SourceConfig> parseRecordingSource(const SourceTable& table) {
  auto c = std::make_unique<RecordingSourceConfig>();
  core::TomlTableReader reader(&table.table, table.source, "recording");
  c->enabled = reader.boolean("enabled", false);
  c->dir = reader.path("dir", "", table.base_dir);
  if (c->enabled) {
    if (c->dir.empty()) reader.fail("dir", "expected the recording folder to play (the source is enabled)");
    try {
      recording::loadRecordingSetup(c->dir);  // --check-config sees a folder that does not read
    } catch (const std::exception& e) {
      reader.fail("dir", std::string("a black-box recording folder: ") + e.what());
    }
  }
  reader.rejectUnknownKeys();
  return c;
}

std::unique_ptr<Source> RecordingSourceConfig::createSource(SourceContext& context) const {
  const auto& c = *this;
  auto source =
      std::make_unique<RecordingSource>(c.table, c.dir, context.playback.at_end, context.playback_clock,
                                        context.source_index, context.addImuRing(c.table), context.addGpsRing(c.table));
  spdlog::info("source recording: {}", c.dir);
  context.logStartsAt(source->firstLogNs());
  return source;
}

RecordingSource::RecordingSource(std::string name, const std::string& dir, AtEnd at_end, const PlaybackClock* clock,
                                 std::uint16_t source_index, SampleRing<ImuRingEntry>* imu_ring,
                                 SampleRing<GpsRingEntry>* gps_ring)
    : AsioSource(std::move(name), source_index, Lifetime::kUntilPlayed, kSnapshotPeriod),
      at_end_(at_end),
      clock_(clock),
      imu_ring_(imu_ring),
      gps_ring_(gps_ring),
      setup_(recording::loadRecordingSetup(dir)),
      timer_(io()) {
  reader_ = std::make_unique<recording::RecordingReader>(setup_);
  spdlog::info("recording {}: recorded by headingd {} from {}", setup_.folder, setup_.program_version,
               setup_.start_utc);
}

RecordingSource::~RecordingSource() { stop(); }

bool RecordingSource::pushStep(const recording::RecordingStep& step, std::int64_t now_ns) {
  using Kind = recording::RecordingStep::Kind;
  switch (step.kind) {
    case Kind::kImu: {
      ImuRingEntry e;
      e.sample = step.imu;
      e.arrival_mono_ns = clock_->dueMonoNs(step.imu.t_ns);
      if (!tryPush(*imu_ring_, e)) return false;
      ++imu_pushed_;
      return true;
    }
    case Kind::kGps: {
      GpsRingEntry e;
      e.observation = step.gps;
      e.arrival_mono_ns = now_ns;
      e.after_imu_samples = static_cast<std::int64_t>(imu_pushed_);
      return tryPush(*gps_ring_, e);
    }
    case Kind::kCalibrationReloaded:
      spdlog::warn(
          "recording {}: the live run re-read its calibration after {} IMU samples (SIGHUP); this replay "
          "keeps the calibration recorded at the start, so its estimates from here on may differ",
          setup_.folder, imu_pushed_);
      return true;
  }
  return true;
}

void RecordingSource::playDue() {
  const std::int64_t now = live::monotonicNs();
  try {
    while (true) {
      if (!pending_) {
        recording::RecordingStep step;
        if (!reader_->next(step)) return finish("");
        pending_ = step;
      }
      if (pending_->kind == recording::RecordingStep::Kind::kImu) {
        const std::int64_t due = clock_->dueMonoNs(pending_->imu.t_ns);
        if (due > now) return waitUntil(due);
      }
      if (!pushStep(*pending_, now)) return waitUntil(now + kRingFullRetryNs);
      pending_.reset();
    }
  } catch (const std::exception& e) {
    finish(e.what());
  }
}

void RecordingSource::waitUntil(std::int64_t mono_ns) {
  takeSnapshot();
  // steady_clock is CLOCK_MONOTONIC on Linux: absolute deadlines, no drift.
  timer_.expires_at(std::chrono::steady_clock::time_point(std::chrono::nanoseconds(mono_ns)));
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) playDue();
  });
}

void RecordingSource::finish(const std::string& error) {
  takeSnapshot();
  const recording::RecordingCounters& c = reader_->counters();
  if (!error.empty()) {
    spdlog::error("recording {}: {}", setup_.folder, error);
    std::lock_guard lock(error_mutex_);
    error_ = error;
  } else if (!reader_->complete()) {
    spdlog::warn(
        "recording {} is incomplete ({} lines lost by the recorder, {} unreadable{}{}): the estimates "
        "are not expected to equal the live run's everywhere",
        setup_.folder, c.lost_lines, c.bad_lines, c.first_bad_line.empty() ? "" : ", first: ", c.first_bad_line,
        c.start_missing ? "; its first segments were deleted by the size cap" : "");
  }
  spdlog::info("recording {} played: {} IMU samples, {} GPS epochs", setup_.folder, c.imu_samples, c.gps_epochs);
  finished_.store(true);
}

void RecordingSource::report(SourceReport& out) const {
  const bool finished = finished_.load();
  {
    std::lock_guard lock(error_mutex_);
    out.state = !error_.empty() ? SourceState::kError : finished ? SourceState::kFinished : SourceState::kRunning;
    out.setLastError(error_);
  }
  std::size_t i = 0;
  out.set(i++, "samples_pushed", pushed());
  withSnapshot([&](const recording::RecordingCounters& c) {
    out.set(i++, "can_frames", c.can_frames);
    out.set(i++, "can_flushes", c.can_flushes);
    out.set(i++, "imu_samples", c.imu_samples);
    out.set(i++, "imu_dropped_live", c.imu_dropped_live);
    out.set(i++, "gps_epochs", c.gps_epochs);
    out.set(i++, "gps_epochs_not_placed", c.gps_epochs_not_placed);
    out.set(i++, "calibration_reloads", c.calibration_reloads);
    out.set(i++, "lost_lines", c.lost_lines);
    out.set(i++, "bad_lines", c.bad_lines);
  });
}

}  // namespace headingd::daemon
