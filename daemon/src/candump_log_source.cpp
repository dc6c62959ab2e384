#include "headingd/daemon/candump_log_source.hpp"

#include <chrono>
#include <spdlog/spdlog.h>
#include <sstream>

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/daemon/can_assembler_report.hpp"
#include "headingd/can/epoch_flush.hpp"
#include "headingd/daemon/clocks.hpp"
#include "headingd/daemon/readable_path.hpp"
#include "headingd/files/numeric_csv.hpp"

namespace headingd::daemon {

std::unique_ptr<SourceConfig> parseCandumpLogSource(const SourceTable& table) {
  auto c = std::make_unique<CandumpLogSourceConfig>();
  core::TomlTableReader candump(&table.table, table.source, "candump_log");
  c->enabled = candump.boolean("enabled", false);
  c->path = readablePath(candump, "path", "", table.base_dir, c->enabled, files::kWholeLogLimit);
  c->can_config_path = readablePath(candump, "can_config", "", table.base_dir, c->enabled, files::kConfigFileLimit);
  if (c->enabled) {
    if (c->path.empty()) candump.fail("path", "expected the candump -l log to play (the source is enabled)");
    if (c->can_config_path.empty()) {
      candump.fail("can_config", "expected a file with the [can] table that decodes the log (e.g. can-headingd.toml)");
    }
    c->can = can::loadCanConfigFile(c->can_config_path);
  }
  candump.rejectUnknownKeys();
  return c;
}

std::unique_ptr<Source> createCandumpLogSource(const SourceConfig& config, SourceContext& context) {
  const auto& c = static_cast<const CandumpLogSourceConfig&>(config);
  auto source = std::make_unique<CandumpLogSource>(c.table, c, context.playback.at_end, context.playback_clock,
                                                   context.source_index, context.addImuRing(c.table));
  spdlog::info("source candump_log: {} ({} frames), decoded by {} (DBC {})", c.path, source->frameCount(),
               c.can_config_path, c.can.dbc_path);
  context.logStartsAt(source->firstLogNs());
  return source;
}

CandumpLogSource::CandumpLogSource(std::string name, const CandumpLogSourceConfig& config, AtEnd at_end,
                                   const PlaybackClock* clock, std::uint16_t source_index,
                                   SampleRing<ImuRingEntry>* imu_ring)
    : AsioSource(std::move(name), source_index, Lifetime::kUntilPlayed, std::chrono::milliseconds(0)),
      at_end_(at_end),
      clock_(clock),
      ring_(imu_ring),
      can_config_(config.can),
      dbc_(can::loadDbcFile(config.can.dbc_path)),
      timer_(io()) {
  codec_ = std::make_unique<can::ImuFrameCodec>(can_config_, dbc_);
  assembler_ = std::make_unique<can::EpochAssembler>(*codec_, can::epochSettingsFrom(can_config_));
  flush_age_ns_ = can::epochFlushAgeNs(can_config_, *codec_);
  {
    // Read whole (a 10 min, 100 Hz log is ~10 MB of text, ~6 MB of frames) so that playing
    // never touches the disk and --check-config sees every line.
    std::istringstream text(files::readMaybeGzipFile(config.path, files::kWholeLogLimit));
    can::CandumpReader reader(text);
    while (const std::optional<can::CanFrame> frame = reader.next()) frames_.push_back(*frame);
    reader_counters_ = reader.counters();
  }
  if (reader_counters_.bad_lines > 0) {
    spdlog::warn("{}: {} line(s) are not candump frames and are skipped; the first, line {}: {}", config.path,
                 reader_counters_.bad_lines, reader_counters_.first_bad_line, reader_counters_.first_bad_reason);
  }
}

CandumpLogSource::~CandumpLogSource() { stop(); }

std::optional<std::int64_t> CandumpLogSource::firstLogNs() const {
  if (frames_.empty()) return std::nullopt;
  return frames_.front().kernel_time_ns;
}

void CandumpLogSource::pushSamples(const can::AssembledSamples& samples) {
  for (int i = 0; i < samples.count; ++i) {
    ImuRingEntry e;
    e.sample = samples.samples[static_cast<std::size_t>(i)];
    e.arrival_mono_ns = clock_->dueMonoNs(e.sample.t_ns);
    push(*ring_, e);
  }
}

void CandumpLogSource::finish() {
  pushSamples(assembler_->finish());
  takeSnapshot();
  finished_.store(true);
}

void CandumpLogSource::playDue() {
  const std::int64_t now = monotonicNs();
  while (next_frame_ < frames_.size() && clock_->dueMonoNs(frames_[next_frame_].kernel_time_ns) <= now) {
    const can::CanFrame& frame = frames_[next_frame_++];
    // The flush on the log's own time: what a receiver with perfect timing would have seen.
    pushSamples(can::flushEpoch(*assembler_, can_config_, flush_age_ns_, frame.kernel_time_ns));
    pushSamples(assembler_->push(frame));
    frames_played_.fetch_add(1, std::memory_order_relaxed);
  }
  if (next_frame_ == frames_.size()) {
    finish();
    return;
  }
  takeSnapshot();
  // steady_clock is CLOCK_MONOTONIC on Linux: absolute deadlines, no drift.
  timer_.expires_at(std::chrono::steady_clock::time_point(
      std::chrono::nanoseconds(clock_->dueMonoNs(frames_[next_frame_].kernel_time_ns))));
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) playDue();
  });
}

void CandumpLogSource::onStart() {
  timer_.expires_at(std::chrono::steady_clock::time_point(std::chrono::nanoseconds(clock_->start_mono_ns)));
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) playDue();
  });
}

void CandumpLogSource::report(SourceReport& out) const {
  const bool finished = finished_.load();
  out.state = finished ? SourceState::kFinished : SourceState::kRunning;
  out.last_error.clear();
  std::size_t i = 0;
  out.set(i++, "frames_in_log", frames_.size());
  out.set(i++, "frames_played", frames_played_.load(std::memory_order_relaxed));
  out.set(i++, "log_bad_lines", reader_counters_.bad_lines);
  out.set(i++, "samples_pushed", pushed());
  out.set(i++, "ring_full_drops", ringFullDrops());
  withSnapshot([&](const can::AssemblerCounters& assembler) { reportAssemblerCounters(out, &i, assembler); });
}

}  // namespace headingd::daemon
