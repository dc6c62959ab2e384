#pragma once
// The black box's recording folder (daemon/README.md, "Black box"): what the daemon wrote
// while it ran live, enough to replay the run bit for bit.
//
//   header.toml              format version, program version, start time, clock offsets, files
//   config.toml              the configuration in use, its file paths pointing at the copies below
//   config.original.toml     the configuration file as it was, byte for byte
//   replay.toml              config.toml with the live sources replaced by [recording] (headingd --config)
//   imu.dbc, wmm.cof, calibration.toml   copies of the files the configuration named (if any)
//   can.000001.log ...       stream "can": candump -l lines, plus the receiver's decisions as notes
//   gps.000001.log ...       stream "gps": the serial bytes with their read times
//   estimator.000001.log ... stream "estimator": where each GPS epoch went into the estimator
//
// Every stream is line-oriented; a line starting with '#' is a note. Times are int64
// nanoseconds on the estimator's axis (CLOCK_MONOTONIC), except the candump times, which are
// that axis plus header.toml's can_time_offset_ns (the wall-clock time at the start), so
// that the can stream is an ordinary candump log (canplayer plays it; it skips the notes).
//
// can:        (1733120000.123456) can0 101#0A0B...     a frame, time = its kernel receive time
//                                                      put on the monotonic clock, in whole µs
//             #flush (1733120000.623456)               the receiver's timer closed the open epoch then
//             #dropped (1733120000.123456)             the sample of that time never reached the
//                                                      estimator (its ring was full)
// gps:        123456789012 r $GPRMC,...*6A\r\n          bytes read at that time (escaped: \r \n \\ \xHH)
//             123456789012 i                          the line went quiet: epoch completed
//             123456789012 e                          end of stream (device lost or closed)
// estimator:  123456789012 g 4711                     the GPS epoch stamped 123456789012 went in
//                                                      after the first 4711 IMU samples
//             123456789012 c 4711                     calibration reloaded (SIGHUP) after 4711 samples
// all:        # lost 12 lines                         the recorder dropped lines here (slow or full disk)
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace headingd::recording {

inline constexpr std::string_view kFormatName = "headingd-recording";
inline constexpr std::int64_t kFormatVersion = 1;
inline constexpr std::string_view kHeaderFile = "header.toml";
inline constexpr std::string_view kConfigFile = "config.toml";
inline constexpr std::string_view kOriginalConfigFile = "config.original.toml";
inline constexpr std::string_view kReplayConfigFile = "replay.toml";
inline constexpr std::string_view kDbcFile = "imu.dbc";
inline constexpr std::string_view kWmmFile = "wmm.cof";
inline constexpr std::string_view kCalibrationFile = "calibration.toml";
inline constexpr std::string_view kCanStream = "can";
inline constexpr std::string_view kGpsStream = "gps";
inline constexpr std::string_view kEstimatorStream = "estimator";

// The longest line a producer hands the recorder (the recorder's own limit is larger).
inline constexpr std::size_t kMaxLineBytes = 232;

// Writes into a caller's buffer and returns the length: no allocation (producers are
// real-time threads).
using LineBuffer = char[kMaxLineBytes];

// "#flush (s.us)" / "#dropped (s.us)": `candump_ns` is the candump time (estimator time plus
// the offset), in whole microseconds.
std::size_t formatCanFlush(std::int64_t candump_ns, LineBuffer& out);
std::size_t formatCanDropped(std::int64_t candump_ns, LineBuffer& out);

// Serial bytes are split so that each escaped line fits: returns how many of `bytes` went
// into `out` (at least one if any are given).
std::size_t formatGpsRead(std::int64_t t_ns, std::span<const std::uint8_t> bytes, LineBuffer& out,
                          std::size_t* bytes_used);
std::size_t formatGpsIdle(std::int64_t t_ns, LineBuffer& out);
std::size_t formatGpsEnd(std::int64_t t_ns, LineBuffer& out);
std::size_t formatGpsPlaced(std::int64_t gps_t_ns, std::uint64_t imu_samples_before, LineBuffer& out);
std::size_t formatCalibrationReloaded(std::int64_t t_ns, std::uint64_t imu_samples_before, LineBuffer& out);

// --- reading ---

enum class CanNote { kFlush, kDropped };
struct ParsedCanNote {
  CanNote kind;
  std::int64_t candump_ns;
};
// A "#flush (...)" or "#dropped (...)" line; nullopt for any other line.
std::optional<ParsedCanNote> parseCanNote(std::string_view line);

// "# lost N lines": N; nullopt for any other line.
std::optional<std::uint64_t> parseLostNote(std::string_view line);

enum class GpsOp { kRead, kIdle, kEnd };
struct ParsedGpsLine {
  std::int64_t t_ns = 0;
  GpsOp op = GpsOp::kRead;
  std::string bytes;  // kRead: the unescaped bytes (reused between calls)
};
// false with `error` set for a malformed line.
bool parseGpsLine(std::string_view line, ParsedGpsLine& out, std::string* error);

enum class EstimatorOp { kGpsPlaced, kCalibrationReloaded };
struct ParsedEstimatorLine {
  std::int64_t t_ns = 0;
  EstimatorOp op = EstimatorOp::kGpsPlaced;
  std::uint64_t imu_samples_before = 0;
};
bool parseEstimatorLine(std::string_view line, ParsedEstimatorLine& out, std::string* error);

// "<folder>/<stream>.<NNNNNN>.log" for segment `index` (1-based).
std::string segmentPath(const std::string& folder, std::string_view stream, std::uint32_t index);

}  // namespace headingd::recording
