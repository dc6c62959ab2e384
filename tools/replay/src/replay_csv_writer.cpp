#include "headingd/replay/replay_csv_writer.hpp"

#include <cstring>
#include <numbers>
#include <stdexcept>

#include "headingd/files/decimal_number.hpp"

namespace headingd::replay {
namespace {

constexpr std::size_t kBufferBytes = 1 << 18;
// Longer than any row: 15 fields of at most ~330 characters each ("%.6f" of DBL_MAX).
constexpr std::size_t kMaxRowBytes = 8192;
constexpr double kDeg = 180.0 / std::numbers::pi;

char* put(char* p, std::string_view text) {
  std::memcpy(p, text.data(), text.size());
  return p + text.size();
}

// printf("%.9g") and ("%.Nf"); the room is kMaxRowBytes.
char* putGeneral9(char* p, double v) { return files::writeGeneral9(p, v); }
char* putFixed(char* p, double v, int digits) { return files::writeFixed(p, v, digits); }

}  // namespace

ReplayCsvWriter::ReplayCsvWriter(const std::string& path, bool with_gps)
    : path_(path), with_gps_(with_gps), buffer_(std::make_unique_for_overwrite<char[]>(kBufferBytes + kMaxRowBytes)) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) throw std::runtime_error(path + ": cannot open for writing");
  used_ = static_cast<std::size_t>(
      put(buffer_.get(), with_gps ? "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg,heading_mag_deg,declination_deg,"
                                     "declination_sigma_deg,declination_source,mount_yaw_deg,heading_true_deg,"
                                     "mag_disturbed\n"
                                   : "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg\n") -
      buffer_.get());
}

ReplayCsvWriter::~ReplayCsvWriter() {
  if (file_ == nullptr) return;
  flush();  // what was estimated before an error stays written
  std::fclose(file_);
}

void ReplayCsvWriter::write(std::int64_t t_ns, const core::HeadingOutput& h) {
  char* p = buffer_.get() + used_;
  const core::EstimatorOutput& e = h.attitude;
  p = putGeneral9(p, static_cast<double>(t_ns) * 1e-9);
  if (!e.valid) {
    p = put(p, with_gps_ ? ",nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,none,nan,nan,0\n"
                         : ",nan,nan,nan,nan,nan,nan,nan\n");
  } else {
    const core::EulerAngles euler = core::eulerZyx(e.q_nb, e.yaw_rad);  // yaw_rad is yawZyx(q_nb)
    for (const double q : {e.q_nb.w(), e.q_nb.x(), e.q_nb.y(), e.q_nb.z()}) {
      *p++ = ',';
      p = putFixed(p, q, 9);
    }
    for (const double angle : {euler.roll_rad, euler.pitch_rad, euler.yaw_rad}) {
      *p++ = ',';
      p = putFixed(p, angle * kDeg, 6);
    }
    if (with_gps_) {
      for (const double angle : {h.heading_mag_rad, h.declination_rad, h.declination_sigma_rad}) {
        *p++ = ',';
        p = putFixed(p, angle * kDeg, 6);
      }
      *p++ = ',';
      p = put(p, core::declinationSourceName(h.declination_sources));
      for (const double angle : {h.mount_yaw_rad, h.heading_true_rad}) {
        *p++ = ',';
        p = putFixed(p, angle * kDeg, 6);
      }
      p = put(p, e.mag_disturbed ? ",1" : ",0");
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
  if (used_ > 0 && std::fwrite(buffer_.get(), 1, used_, file_) != used_) failed_ = true;
  used_ = 0;
}

void ReplayCsvWriter::close() {
  if (file_ == nullptr) return;
  flush();
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (failed_ || !closed) throw std::runtime_error(path_ + ": write failed");
}

}  // namespace headingd::replay
