#include "headingd/recording/stream_recorders.hpp"

#include "headingd/can/candump_log.hpp"
#include "headingd/recording/recording_format.hpp"

namespace headingd::recording {

CanStreamRecorder::CanStreamRecorder(LineSink& sink, std::string interface, std::int64_t can_time_offset_ns)
    : sink_(sink), interface_(std::move(interface)), offset_ns_(can_time_offset_ns) {}

void CanStreamRecorder::frame(const can::CanFrame& frame) {
  can::CanFrame stamped = frame;
  stamped.t_ns += offset_ns_;
  char line[can::kCandumpLineMaxBytes];
  sink_.write(std::string_view(line, can::formatCandumpLine(stamped, interface_, line)));
}

void CanStreamRecorder::flushed(std::int64_t now_ns) {
  LineBuffer line;
  sink_.write(std::string_view(line, formatCanFlush(now_ns + offset_ns_, line)));
}

void CanStreamRecorder::dropped(std::int64_t sample_t_ns) {
  LineBuffer line;
  sink_.write(std::string_view(line, formatCanDropped(sample_t_ns + offset_ns_, line)));
}

void GpsStreamRecorder::fed(std::span<const std::uint8_t> bytes, std::int64_t receive_ns) {
  // A long read becomes several lines of the same time: the assembler works byte by byte,
  // so feeding the pieces one after the other is the same as feeding the whole.
  LineBuffer line;
  while (!bytes.empty()) {
    std::size_t used = 0;
    const std::size_t n = formatGpsRead(receive_ns, bytes, line, &used);
    sink_.write(std::string_view(line, n));
    bytes = bytes.subspan(used);
  }
}

void GpsStreamRecorder::epochCompleted(std::int64_t now_ns) {
  LineBuffer line;
  sink_.write(std::string_view(line, formatGpsIdle(now_ns, line)));
}

void GpsStreamRecorder::streamEnded(std::int64_t now_ns) {
  LineBuffer line;
  sink_.write(std::string_view(line, formatGpsEnd(now_ns, line)));
}

void EstimatorStreamRecorder::gpsPlaced(std::int64_t gps_t_ns, std::uint64_t imu_samples_before) {
  LineBuffer line;
  sink_.write(std::string_view(line, formatGpsPlaced(gps_t_ns, imu_samples_before, line)));
}

void EstimatorStreamRecorder::calibrationReloaded(std::int64_t t_ns, std::uint64_t imu_samples_before) {
  LineBuffer line;
  sink_.write(std::string_view(line, formatCalibrationReloaded(t_ns, imu_samples_before, line)));
}

}  // namespace headingd::recording
