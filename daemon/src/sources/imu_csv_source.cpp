#include "headingd/daemon/sources/imu_csv_source.hpp"

#include <spdlog/spdlog.h>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/daemon/sources/median_step.hpp"
#include "headingd/daemon/sources/readable_path.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/nmea_epochs.hpp"
#include "headingd/live/clocks.hpp"

namespace headingd::daemon {

std::unique_ptr<SourceConfig> parseImuCsvSource(const SourceTable& table) {
  auto c = std::make_unique<ImuCsvSourceConfig>();
  core::TomlTableReader csv(&table.table, table.source, "imu_csv");
  c->enabled = csv.boolean("enabled", c->enabled);
  c->imu_csv_path = readablePath(csv, "path", "", table.base_dir, c->enabled, 0);
  if (c->enabled && c->imu_csv_path.empty())
    csv.fail("path", "expected the IMU CSV file to play (the source is enabled)");
  c->nmea_path = readablePath(csv, "nmea", "", table.base_dir, c->enabled, files::kWholeLogLimit);
  c->nmea_first_epoch_t_s = csv.number("nmea_first_epoch_t_s", 0.0, -1e9, 1e9, "s");
  c->speed = csv.number("speed", c->speed, 0.01, 1000.0, "x real time");
  c->start_delay_s = csv.number("start_delay_s", c->start_delay_s, 0.0, 3600.0, "s");
  const std::string at_end = csv.choice("at_end", "stay", {"stay", "exit", "loop"});
  c->at_end = at_end == "exit" ? AtEnd::kExit : at_end == "loop" ? AtEnd::kLoop : AtEnd::kStay;
  c->monotonic_time = csv.choice("time_axis", "file", {"file", "monotonic"}) == "monotonic";
  if (c->monotonic_time && c->speed != 1.0) {
    csv.fail("time_axis",
             "\"monotonic\" needs speed = 1.0 (at another speed the file's time steps would not be the clock's)");
  }
  c->no_mag = csv.boolean("no_mag", c->no_mag);
  csv.rejectUnknownKeys();
  return c;
}

std::unique_ptr<Source> ImuCsvSourceConfig::createSource(SourceContext& context) const {
  const auto& c = *this;
  SampleRing<ImuRingEntry>* imu_ring = context.addImuRing(c.table);
  SampleRing<GpsRingEntry>* gps_ring = c.nmea_path.empty() ? nullptr : context.addGpsRing(c.table);
  auto source = std::make_unique<ImuCsvSource>(c.table, c, context.source_index, imu_ring, gps_ring);
  spdlog::info("source imu_csv: {} ({} samples{}), speed {}x, at end: {}", c.imu_csv_path, source->imuSampleCount(),
               c.nmea_path.empty()
                   ? std::string()
                   : ", GPS " + c.nmea_path + " (" + std::to_string(source->gpsEpochCount()) + " epochs)",
               c.speed, atEndName(c.at_end));
  return source;
}

ImuCsvSource::ImuCsvSource(std::string name, const ImuCsvSourceConfig& config, std::uint16_t source_index,
                           SampleRing<ImuRingEntry>* imu_ring, SampleRing<GpsRingEntry>* gps_ring)
    : name_(std::move(name)), config_(config), source_index_(source_index), imu_ring_(imu_ring), gps_ring_(gps_ring) {
  imu_ = files::readImuCsv(config_.imu_csv_path,
                           config_.no_mag ? files::MagColumns::kIgnored : files::MagColumns::kRequired);
  if (!config_.nmea_path.empty()) {
    files::NmeaEpochs epochs = files::readNmeaEpochs(config_.nmea_path, config_.nmea_first_epoch_t_s);
    gps_ = std::move(epochs.epochs);
    nmea_counters_ = epochs.counters;
  }
  if (imu_.size() >= 2) {
    // One loop later = the file's length plus its median sample period, so the loop seam
    // looks like one ordinary sample step to the estimator's gate.
    std::vector<std::int64_t> steps;
    for (std::size_t i = 1; i < std::min<std::size_t>(imu_.size(), 1001); ++i)
      steps.push_back(imu_[i].t_ns - imu_[i - 1].t_ns);
    loop_length_ns_ = imu_.back().t_ns - imu_.front().t_ns + std::max<std::int64_t>(*medianStep(std::move(steps)), 1);
  }
}

ImuCsvSource::~ImuCsvSource() { stop(); }

void ImuCsvSource::start() {
  thread_ = std::thread([this] {
    runThreadStartHook();
    run();
  });
}

void ImuCsvSource::stop() {
  {
    std::lock_guard lock(mutex_);
    stop_requested_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool ImuCsvSource::sleepUntil(std::int64_t mono_ns) {
  // std::chrono::steady_clock is CLOCK_MONOTONIC on Linux, the clock of mono_ns.
  const std::chrono::steady_clock::time_point until{std::chrono::nanoseconds(mono_ns)};
  std::unique_lock lock(mutex_);
  return !wake_.wait_until(lock, until, [this] { return stop_requested_; });
}

void ImuCsvSource::run() {
  if (imu_.empty()) {
    state_ = SourceState::kFinished;
    wants_exit_ = config_.at_end == AtEnd::kExit;
    return;
  }
  const std::int64_t file_t0 = imu_.front().t_ns;
  const std::int64_t start_mono = live::monotonicNs() + static_cast<std::int64_t>(config_.start_delay_s * 1e9);
  // Play time of a file time `t` (ns) in loop `loop`.
  const double speed = config_.speed;
  auto playAt = [&](std::int64_t t_ns) {
    return start_mono + static_cast<std::int64_t>(std::llround(static_cast<double>(t_ns - file_t0) / speed));
  };
  state_ = SourceState::kRunning;
  // time_axis = "monotonic": file time t is sent as the monotonic time it is played at.
  const std::int64_t axis_offset = config_.monotonic_time ? start_mono - file_t0 : 0;
  for (std::int64_t offset = axis_offset;; offset += loop_length_ns_) {
    std::size_t next_imu = 0, next_gps = 0;
    while (next_imu < imu_.size() || next_gps < gps_.size()) {
      // Everything is played at its own due time, in time order (a tie: the IMU sample
      // first): this is when the data arrives, as from live sensors. The order the estimator
      // sees is the loop's (core/imu_then_gps_order.hpp: an epoch after the first IMU sample
      // at or after it, as in headingd-replay), so it is not repeated here.
      const bool imu_next =
          next_gps >= gps_.size() || (next_imu < imu_.size() && imu_[next_imu].t_ns <= gps_[next_gps].t_ns);
      const std::int64_t t = imu_next ? imu_[next_imu].t_ns : gps_[next_gps].t_ns;
      const std::int64_t due = playAt(t + offset - axis_offset);
      if (due > live::monotonicNs() && !sleepUntil(due)) return;
      const std::int64_t now = live::monotonicNs();
      if (imu_next) {
        ImuRingEntry e;
        e.sample = imu_[next_imu++];
        e.sample.t_ns += offset;
        e.arrival_mono_ns = now;
        e.source_index = source_index_;
        (imu_ring_->push(e) ? imu_pushed_ : imu_dropped_).fetch_add(1, std::memory_order_relaxed);
      } else {
        GpsRingEntry e;
        e.observation = gps_[next_gps++];
        e.observation.t_ns += offset;
        e.arrival_mono_ns = now;
        e.source_index = source_index_;
        const bool pushed = gps_ring_ != nullptr && gps_ring_->push(e);
        (pushed ? gps_pushed_ : gps_dropped_).fetch_add(1, std::memory_order_relaxed);
      }
    }
    loops_.fetch_add(1, std::memory_order_relaxed);
    if (config_.at_end != AtEnd::kLoop) break;
  }
  state_ = SourceState::kFinished;
  wants_exit_ = config_.at_end == AtEnd::kExit;
}

void ImuCsvSource::report(SourceReport& out) const {
  out.state = state_.load();
  out.last_error.clear();
  std::size_t i = 0;
  out.set(i++, "imu_samples_in_file", imu_.size());
  out.set(i++, "imu_pushed", imu_pushed_.load(std::memory_order_relaxed));
  out.set(i++, "imu_ring_full_drops", imu_dropped_.load(std::memory_order_relaxed));
  out.set(i++, "gps_epochs_in_file", gps_.size());
  out.set(i++, "gps_pushed", gps_pushed_.load(std::memory_order_relaxed));
  out.set(i++, "gps_ring_full_drops", gps_dropped_.load(std::memory_order_relaxed));
  out.set(i++, "loops_played", loops_.load(std::memory_order_relaxed));
  if (!config_.nmea_path.empty()) {
    nmea::forEachCounter(nmea_counters_, [&](const char* name, std::uint64_t v) { out.set(i++, "nmea_", name, v); });
  }
}

}  // namespace headingd::daemon
