#include "headingd/replay/replay_csv_writer.hpp"

#include <cstring>
#include <numbers>
#include <stdexcept>

#include "headingd/core/angles.hpp"
#include "headingd/files/decimal_number.hpp"

namespace headingd::replay {
namespace {

// Written out in 64 KiB pieces: a larger buffer costs more first-touch page faults than the
// write calls it saves (see line_reader.cpp).
constexpr std::size_t kBufferBytes = 1 << 16;
// Longer than any row: 15 fields of at most ~330 characters each ("%.6f" of DBL_MAX).
constexpr std::size_t kMaxRowBytes = 8192;
using core::kDegPerRad;

char* put(char* p, std::string_view text) {
  std::memcpy(p, text.data(), text.size());
  return p + text.size();
}

// Seconds with all nine decimals, from the integer nanoseconds (exact: a UNIX time of 1.7e9 s
// keeps its nanoseconds, which "%.9g" would round to 1.7e+09).
char* putSecondsNs(char* p, std::int64_t t_ns) {
  // Magnitudes as unsigned, so INT64_MIN has one too.
  const bool negative = t_ns < 0;
  const std::uint64_t magnitude = negative ? 0 - static_cast<std::uint64_t>(t_ns) : static_cast<std::uint64_t>(t_ns);
  if (negative) *p++ = '-';
  return files::writeScaledDecimal(p, magnitude, 9);
}

// printf("%.Nf"); the room is kMaxRowBytes.
char* putFixed(char* p, double v, int digits) { return files::writeFixed(p, v, digits); }

}  // namespace

ReplayCsvWriter::ReplayCsvWriter(const std::string& path, bool with_gps)
    : path_(path), with_gps_(with_gps), buffer_(std::make_unique_for_overwrite<char[]>(kBufferBytes + kMaxRowBytes)) {
  file_ = std::make_unique<files::OutputFile>(path);
  used_ = static_cast<std::size_t>(
      put(buffer_.get(), with_gps ? "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg,heading_mag_deg,declination_deg,"
                                    "declination_sigma_deg,declination_source,mount_yaw_deg,heading_true_deg,"
                                    "mag_disturbed,heading_mag_sigma_deg,heading_true_sigma_deg\n"
                                  : "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg,heading_sigma_deg\n") -
      buffer_.get());
}

// Not closed: an error stopped the replay, and the output file is dropped (never half-written).
ReplayCsvWriter::~ReplayCsvWriter() = default;

void ReplayCsvWriter::write(std::int64_t t_ns, const core::HeadingOutput& h) {
  char* p = buffer_.get() + used_;
  const core::EstimatorOutput& e = h.attitude;
  p = putSecondsNs(p, t_ns);
  if (!e.valid) {
    p = put(p, with_gps_ ? ",nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,none,nan,nan,0,nan,nan\n"
                         : ",nan,nan,nan,nan,nan,nan,nan,nan\n");
  } else {
    const core::EulerAngles euler = core::eulerZyx(e.q_nb, e.yaw_rad);  // yaw_rad is yawZyx(q_nb)
    for (const double q : {e.q_nb.w(), e.q_nb.x(), e.q_nb.y(), e.q_nb.z()}) {
      *p++ = ',';
      p = putFixed(p, q, 9);
    }
    for (const double angle : {euler.roll_rad, euler.pitch_rad, euler.yaw_rad}) {
      *p++ = ',';
      p = putFixed(p, angle * kDegPerRad, 6);
    }
    if (with_gps_) {
      for (const double angle : {h.heading_mag_rad, h.declination_rad, h.declination_sigma_rad}) {
        *p++ = ',';
        p = putFixed(p, angle * kDegPerRad, 6);
      }
      *p++ = ',';
      p = put(p, core::declinationSourceName(h.declination_sources));
      for (const double angle : {h.mount_yaw_rad, h.heading_true_rad}) {
        *p++ = ',';
        p = putFixed(p, angle * kDegPerRad, 6);
      }
      p = put(p, e.mag_disturbed ? ",1" : ",0");
      for (const double sigma : {h.heading_mag_sigma_rad, h.heading_true_sigma_rad}) {
        *p++ = ',';
        p = putFixed(p, sigma * kDegPerRad, 6);
      }
    } else {
      *p++ = ',';
      p = putFixed(p, h.heading_mag_sigma_rad * kDegPerRad, 6);
    }
    *p++ = '\n';
  }
  used_ = static_cast<std::size_t>(p - buffer_.get());
  flushIfFull();
}

void ReplayCsvWriter::flushIfFull() {
  if (used_ >= kBufferBytes) flush();
}

void ReplayCsvWriter::flush() {
  file_->write(std::string_view(buffer_.get(), used_));
  used_ = 0;
}

void ReplayCsvWriter::close() {
  if (file_ == nullptr) return;
  flush();
  file_->commit();  // throws files::FileError naming the file
  file_.reset();
}

}  // namespace headingd::replay
