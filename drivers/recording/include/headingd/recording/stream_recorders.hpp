#pragma once
// The producers' side of the black box: each live thread formats what it does into lines of
// its stream (recording_format.hpp) and hands them to a LineSink (the daemon's recorder),
// which never blocks. No allocation here: these run on real-time threads.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "headingd/can/can_frame.hpp"
#include "headingd/nmea/serial_epoch_assembler.hpp"

namespace headingd::recording {

// Where lines go. write() must not block; false = the line was dropped (the sink counts it
// and notes the loss in the stream).
class LineSink {
 public:
  virtual ~LineSink() = default;
  virtual bool write(std::string_view line) = 0;
};

// The CAN receiver's thread: frames as the epoch assembler got them, and its decisions that
// depend on timing (timer flushes) or on the estimator's ring (drops).
class CanStreamRecorder {
 public:
  // `can_time_offset_ns`: added to estimator times to give candump times (whole µs).
  CanStreamRecorder(LineSink& sink, std::string interface, std::int64_t can_time_offset_ns);
  // `frame.t_ns` on the estimator's axis, as given to the assembler.
  void frame(const can::CanFrame& frame);
  void flushed(std::int64_t now_ns);
  void dropped(std::int64_t sample_t_ns);

 private:
  LineSink& sink_;
  std::string interface_;
  std::int64_t offset_ns_;
};

// The serial reader's thread: every call its epoch assembler gets.
class GpsStreamRecorder : public nmea::AssemblerInputTap {
 public:
  explicit GpsStreamRecorder(LineSink& sink) : sink_(sink) {}
  void fed(std::span<const std::uint8_t> bytes, std::int64_t receive_ns) override;
  void epochCompleted(std::int64_t now_ns) override;
  void streamEnded(std::int64_t now_ns) override;

 private:
  LineSink& sink_;
};

// The estimator's thread: where each GPS epoch went in, counted in IMU samples.
class EstimatorStreamRecorder {
 public:
  explicit EstimatorStreamRecorder(LineSink& sink) : sink_(sink) {}
  void gpsPlaced(std::int64_t gps_t_ns, std::uint64_t imu_samples_before);
  void calibrationReloaded(std::int64_t t_ns, std::uint64_t imu_samples_before);

 private:
  LineSink& sink_;
};

}  // namespace headingd::recording
