#include "headingd/daemon/sources/candump_log_source.hpp"

#include <spdlog/spdlog.h>
#include <chrono>
#include <sstream>

#include "headingd/can/epoch_flush.hpp"
#include "headingd/core/toml_table_reader.hpp"
#include "headingd/daemon/sources/can_assembler_report.hpp"
#include "headingd/daemon/sources/log_frame_times.hpp"
#include "headingd/daemon/sources/median_step.hpp"
#include "headingd/daemon/sources/readable_path.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/input_file.hpp"
#include "headingd/live/clocks.hpp"

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

std::unique_ptr<Source> CandumpLogSourceConfig::createSource(SourceContext& context) const {
  const auto& c = *this;
  auto source = std::make_unique<CandumpLogSource>(c.table, c, context.playback.at_end, context.playback_clock,
                                                   context.source_index, context.addImuRing(c.table));
  spdlog::info("source candump_log: {} ({} frames), decoded by {} (DBC {})", c.path, source->frameCount(),
               c.can_config_path, c.can.dbc_path);
  context.logStartsAt(source->firstLogNs());
  context.logEndsAt(source->lastLogNs(), source->sampleStepNs());
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
  // Read whole (a 10 min, 100 Hz log is ~10 MB of text, ~6 MB of frames) so that playing
  // never touches the disk and --check-config sees every line. A gzip log cut short (a power
  // loss while recording) is played as far as it goes, and said so.
  const files::MaybeCutText log = files::readMaybeGzipLog(config.path, files::kWholeLogLimit);
  end_missing_ = log.end_missing;
  std::vector<can::CanFrame> all;
  std::vector<std::uint64_t> lines;  // of each frame, for the messages below
  {
    std::istringstream text(log.text);
    can::CandumpReader reader(text);
    while (const std::optional<can::CanFrame> frame = reader.next()) {
      all.push_back(*frame);
      lines.push_back(reader.counters().lines);
    }
    reader_counters_ = reader.counters();
  }
  if (reader_counters_.bad_lines > 0) {
    spdlog::warn("{}: {} line(s) are not candump frames and are skipped; the first, line {}: {}", config.path,
                 reader_counters_.bad_lines, reader_counters_.first_bad_line, reader_counters_.first_bad_reason);
  }
  if (end_missing_) {
    spdlog::warn(
        "{}: the gzip log is cut short: {} bytes of text, {} frames read; the end of the log is missing, "
        "what was read is played",
        config.path, log.text.size(), all.size());
  }
  placeFrames(config.path, all, lines);
}

void CandumpLogSource::placeFrames(const std::string& path, const std::vector<can::CanFrame>& all,
                                   const std::vector<std::uint64_t>& lines) {
  std::vector<std::int64_t> log_ns(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) log_ns[i] = all[i].t_ns;
  const LogFrameTimes times = placeLogFrames(log_ns);
  time_outlier_frames_ = times.outlier_frames;
  time_steps_ = times.time_steps;
  frames_.reserve(all.size() - times.outlier_frames);
  play_ns_.reserve(all.size() - times.outlier_frames);
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (times.skipped[i]) continue;
    frames_.push_back(all[i]);
    play_ns_.push_back(times.play_ns[i]);
  }
  std::vector<std::int64_t> steps;
  std::optional<std::int64_t> previous;
  for (std::size_t i = 0; i < frames_.size() && steps.size() < 1000; ++i) {
    if (frames_[i].id != frames_.front().id || frames_[i].extended != frames_.front().extended) continue;
    if (previous && play_ns_[i] > *previous) steps.push_back(play_ns_[i] - *previous);
    previous = play_ns_[i];
  }
  sample_step_ns_ = medianStep(std::move(steps));
  auto seconds = [](std::int64_t ns) { return static_cast<double>(ns) * 1e-9; };
  if (times.outlier_frames > 0) {
    const auto at = static_cast<std::size_t>(times.first_outlier_index);
    spdlog::warn(
        "{}: {} frame(s) whose time lies more than {:g} s from the frames around them are skipped; the "
        "first, line {}: ({:.6f})",
        path, times.outlier_frames, seconds(LogFrameTimes::kJumpNs), lines[at], seconds(log_ns[at]));
  }
  if (times.time_steps > 0) {
    const auto at = static_cast<std::size_t>(times.first_step_index);
    spdlog::warn(
        "{}: the log's time steps {} time(s) (back by more than {:g} s or ahead by more than {:g} s) and is "
        "played on without waiting; the first, line {}: ({:.6f})",
        path, times.time_steps, seconds(LogFrameTimes::kJumpNs), seconds(LogFrameTimes::kLongestGapNs), lines[at],
        seconds(log_ns[at]));
  }
}

CandumpLogSource::~CandumpLogSource() { stop(); }

std::optional<std::int64_t> CandumpLogSource::firstLogNs() const {
  if (frames_.empty()) return std::nullopt;
  return play_ns_.front();
}

std::optional<std::int64_t> CandumpLogSource::lastLogNs() const {
  if (frames_.empty()) return std::nullopt;
  return play_ns_.back();
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

bool CandumpLogSource::startNextLoop() {
  if (clock_->loop_ns <= 0 || frames_.empty()) return false;  // loop_ns > 0: at_end = "loop"
  // The log's epoch counters start again (its last and first may even be equal).
  pushSamples(assembler_->restartStream());
  loop_offset_ns_ += clock_->loop_ns;
  next_frame_ = 0;
  loops_played_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void CandumpLogSource::playDue() {
  const std::int64_t now = live::monotonicNs();
  for (;;) {
    while (next_frame_ < frames_.size() && clock_->dueMonoNs(play_ns_[next_frame_] + loop_offset_ns_) <= now) {
      can::CanFrame frame = frames_[next_frame_++];
      frame.t_ns += loop_offset_ns_;
      // The flush on the log's own time: what a receiver with perfect timing would have seen.
      pushSamples(can::flushEpoch(*assembler_, can_config_, flush_age_ns_, frame.t_ns));
      pushSamples(assembler_->push(frame));
      full_scale_warning_.look(assembler_->counters(), now, "candump_log");
      frames_played_.fetch_add(1, std::memory_order_relaxed);
    }
    if (next_frame_ < frames_.size()) break;
    if (!startNextLoop()) {
      finish();
      return;
    }
  }
  takeSnapshot();
  // steady_clock is CLOCK_MONOTONIC on Linux: absolute deadlines, no drift.
  timer_.expires_at(std::chrono::steady_clock::time_point(
      std::chrono::nanoseconds(clock_->dueMonoNs(play_ns_[next_frame_] + loop_offset_ns_))));
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
  out.set(i++, "frames_in_log", reader_counters_.frames);
  out.set(i++, "frames_played", frames_played_.load(std::memory_order_relaxed));
  out.set(i++, "loops_played", loops_played_.load(std::memory_order_relaxed));
  out.set(i++, "log_bad_lines", reader_counters_.bad_lines);
  out.set(i++, "log_end_missing", end_missing_ ? 1u : 0u);
  out.set(i++, "time_outlier_frames", time_outlier_frames_);
  out.set(i++, "time_steps", time_steps_);
  out.set(i++, "samples_pushed", pushed());
  out.set(i++, "ring_full_drops", ringFullDrops());
  withSnapshot([&](const can::AssemblerCounters& assembler) { reportAssemblerCounters(out, &i, assembler); });
}

}  // namespace headingd::daemon
