#include "headingd/recording/recording_reader.hpp"

#include <stdexcept>

#include "headingd/can/candump_log.hpp"
#include "headingd/can/epoch_flush.hpp"
#include "headingd/nmea/gps_observation_from_fix.hpp"
#include "headingd/recording/recording_format.hpp"

namespace headingd::recording {

RecordingReader::RecordingReader(const RecordingSetup& setup)
    : setup_(setup),
      can_lines_(setup.folder, kCanStream),
      gps_lines_(setup.folder, kGpsStream),
      estimator_lines_(setup.folder, kEstimatorStream) {
  if (setup_.can) {
    dbc_.emplace(can::loadDbcFile(setup_.can->dbc_path));
    codec_ = std::make_unique<can::ImuFrameCodec>(*setup_.can, *dbc_);
    can_assembler_ = std::make_unique<can::EpochAssembler>(*codec_, can::epochSettingsFrom(*setup_.can));
    flush_age_ns_ = can::epochFlushAgeNs(*setup_.can, *codec_);
  }
  if (setup_.gps) {
    gps_assembler_ = std::make_unique<nmea::EpochAssembler>(
        setup_.gps->parser, [this](const nmea::Fix& fix, std::int64_t receive_ns) {
          gps_queue_.push_back(nmea::gpsObservationFromFix(fix, receive_ns));
        });
  }
  for (const StreamLines* s : {&can_lines_, &gps_lines_, &estimator_lines_}) {
    if (s->firstSegment() > 1) counters_.start_missing = true;
  }
}

RecordingReader::~RecordingReader() = default;

bool RecordingReader::complete() const {
  return counters_.lost_lines == 0 && counters_.bad_lines == 0 && !counters_.start_missing &&
         counters_.calibration_reloads == 0;
}

void RecordingReader::badLine(const StreamLines& stream, const std::string& what) {
  if (counters_.bad_lines++ == 0) counters_.first_bad_line = stream.where() + ": expected " + what;
}

void RecordingReader::onCanLine(std::string_view line) {
  if (line.empty()) return;
  if (line.front() == '#') {
    if (const auto lost = parseLostNote(line)) {
      counters_.lost_lines += *lost;
    } else if (const auto note = parseCanNote(line)) {
      const std::int64_t t = note->candump_ns - setup_.can_time_offset_ns;
      if (note->kind == CanNote::kFlush) {
        ++counters_.can_flushes;
        const can::AssembledSamples s = can::flushEpoch(*can_assembler_, *setup_.can, flush_age_ns_, t);
        for (int i = 0; i < s.count; ++i) imu_queue_.push_back(s.samples[static_cast<std::size_t>(i)]);
      } else {
        // The sample this note is about was assembled by the line before: still queued.
        for (auto it = imu_queue_.rbegin(); it != imu_queue_.rend(); ++it) {
          if (it->t_ns == t) {
            imu_queue_.erase(std::next(it).base());
            ++counters_.imu_dropped_live;
            return;
          }
        }
        badLine(can_lines_, "a '#dropped' note right after the frame that completed that sample");
      }
    }
    return;  // other notes are for people
  }
  std::string reason;
  const auto logged = can::parseCandumpLine(line, &reason);
  if (!logged) return badLine(can_lines_, reason);
  can::CanFrame frame = logged->frame;
  frame.t_ns -= setup_.can_time_offset_ns;
  ++counters_.can_frames;
  const can::AssembledSamples s = can_assembler_->push(frame);
  for (int i = 0; i < s.count; ++i) imu_queue_.push_back(s.samples[static_cast<std::size_t>(i)]);
}

bool RecordingReader::fillImu() {
  if (!can_assembler_) return false;
  std::string_view line;
  // A sample is handed out only once the notes after its line are read: a '#dropped' note
  // follows the frame (or flush) that assembled the sample it is about.
  while (true) {
    if (!imu_queue_.empty()) {
      if (!can_lines_.next(line)) return true;
      onCanLine(line);
      if (!line.empty() && line.front() == '#') continue;
      return !imu_queue_.empty();
    }
    if (!can_lines_.next(line)) return false;
    onCanLine(line);
  }
}

void RecordingReader::onGpsLine(std::string_view line) {
  if (line.empty()) return;
  if (line.front() == '#') {
    if (const auto lost = parseLostNote(line)) counters_.lost_lines += *lost;
    return;
  }
  ParsedGpsLine parsed;
  if (!parseGpsLine(line, parsed, &parse_error_)) return badLine(gps_lines_, parse_error_);
  switch (parsed.op) {
    case GpsOp::kRead:
      gps_assembler_->feed(std::span(reinterpret_cast<const std::uint8_t*>(parsed.bytes.data()), parsed.bytes.size()),
                           parsed.t_ns);
      break;
    case GpsOp::kIdle: gps_assembler_->completeEpoch(); break;
    case GpsOp::kEnd: gps_assembler_->endOfStream(); break;
  }
}

bool RecordingReader::fillGps() {
  if (!gps_assembler_) return false;
  std::string_view line;
  while (gps_queue_.empty()) {
    if (!gps_lines_.next(line)) return false;
    onGpsLine(line);
  }
  return true;
}

void RecordingReader::loadPlacement() {
  placement_loaded_ = false;
  std::string_view line;
  while (!placements_done_) {
    if (!estimator_lines_.next(line)) {
      placements_done_ = true;
      return;
    }
    if (line.empty()) continue;
    if (line.front() == '#') {
      if (const auto lost = parseLostNote(line)) counters_.lost_lines += *lost;
      continue;
    }
    ParsedEstimatorLine parsed;
    if (!parseEstimatorLine(line, parsed, &parse_error_)) {
      badLine(estimator_lines_, parse_error_);
      continue;
    }
    placement_loaded_ = true;
    placement_t_ns_ = parsed.t_ns;
    placement_is_reload_ = parsed.op == EstimatorOp::kCalibrationReloaded;
    placement_after_ = parsed.imu_samples_before;
    return;
  }
}

bool RecordingReader::readStep(RecordingStep& step) {
  if (!placement_loaded_) loadPlacement();
  if (placement_loaded_ && placement_after_ < imu_handed_out_) {
    throw std::runtime_error(estimator_lines_.where() + ": placed after " + std::to_string(placement_after_) +
                             " IMU samples, but " + std::to_string(imu_handed_out_) +
                             " were handed out already: the streams do not belong together");
  }
  if (placement_loaded_ && placement_after_ == imu_handed_out_) {
    placement_loaded_ = false;
    if (placement_is_reload_) {
      ++counters_.calibration_reloads;
      step.kind = RecordingStep::Kind::kCalibrationReloaded;
      return true;
    }
    // The epoch the estimator took; those assembled before it never reached it (ring full,
    // or the run stopped first).
    while (true) {
      if (!fillGps()) {
        throw std::runtime_error(estimator_lines_.where() + ": a GPS epoch stamped " + std::to_string(placement_t_ns_) +
                                 " ns went into the estimator, but the gps stream has no such epoch");
      }
      const core::GpsObservation epoch = gps_queue_.front();
      gps_queue_.pop_front();
      if (epoch.t_ns == placement_t_ns_) {
        step.kind = RecordingStep::Kind::kGps;
        step.gps = epoch;
        ++counters_.gps_epochs;
        return true;
      }
      ++counters_.gps_epochs_not_placed;
    }
  }
  if (fillImu()) {
    step.kind = RecordingStep::Kind::kImu;
    step.imu = imu_queue_.front();
    imu_queue_.pop_front();
    ++imu_handed_out_;
    ++counters_.imu_samples;
    return true;
  }
  if (placement_loaded_) {
    throw std::runtime_error(estimator_lines_.where() + ": placed after " + std::to_string(placement_after_) +
                             " IMU samples, but the can stream holds only " + std::to_string(imu_handed_out_));
  }
  return false;
}

bool RecordingReader::next(RecordingStep& step) {
  if (peeked_) {
    step = *peeked_;
    peeked_.reset();
    return true;
  }
  return readStep(step);
}

std::optional<std::int64_t> RecordingReader::firstTimeNs() {
  if (!peeked_) {
    RecordingStep step;
    if (!readStep(step)) return std::nullopt;
    peeked_ = step;
  }
  switch (peeked_->kind) {
    case RecordingStep::Kind::kImu: return peeked_->imu.t_ns;
    case RecordingStep::Kind::kGps: return peeked_->gps.t_ns;
    case RecordingStep::Kind::kCalibrationReloaded: return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace headingd::recording
