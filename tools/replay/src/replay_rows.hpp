#pragma once
// Temporary: the replay's output rows (the streaming writer replaces this).
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "headingd/core/heading_pipeline.hpp"

namespace headingd::replay {

class RowWriter {
 public:
  RowWriter(const std::string& path, bool with_gps) : path_(path), with_gps_(with_gps) {
    f_ = std::fopen(path.c_str(), "w");
    if (f_ == nullptr) throw std::runtime_error(path + ": cannot open for writing");
    std::fputs(with_gps ? "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg,heading_mag_deg,declination_deg,"
                          "declination_sigma_deg,declination_source,mount_yaw_deg,heading_true_deg,mag_disturbed\n"
                        : "t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg\n",
               f_);
  }
  void write(std::int64_t t_ns, const core::HeadingOutput& h) {
    constexpr double kDeg = 180.0 / std::numbers::pi;
    const auto& e = h.attitude;
    const double t = static_cast<double>(t_ns) * 1e-9;
    if (!e.valid) {
      std::fprintf(f_, with_gps_ ? "%.9g,nan,nan,nan,nan,nan,nan,nan,nan,nan,nan,none,nan,nan,0\n"
                                 : "%.9g,nan,nan,nan,nan,nan,nan,nan\n", t);
      return;
    }
    const core::EulerAngles euler = core::eulerZyx(e.q_nb);
    std::fprintf(f_, "%.9g,%.9f,%.9f,%.9f,%.9f,%.6f,%.6f,%.6f", t, e.q_nb.w(), e.q_nb.x(), e.q_nb.y(), e.q_nb.z(),
                 euler.roll_rad * kDeg, euler.pitch_rad * kDeg, euler.yaw_rad * kDeg);
    if (with_gps_) {
      std::fprintf(f_, ",%.6f,%.6f,%.6f,%s,%.6f,%.6f,%d", h.heading_mag_rad * kDeg, h.declination_rad * kDeg,
                   h.declination_sigma_rad * kDeg, core::declinationSourceName(h.declination_sources),
                   h.mount_yaw_rad * kDeg, h.heading_true_rad * kDeg, e.mag_disturbed ? 1 : 0);
    }
    std::fputc('\n', f_);
  }
  void close() {
    if (f_ != nullptr && std::fclose(f_) != 0) throw std::runtime_error(path_ + ": write failed");
    f_ = nullptr;
  }
  ~RowWriter() {
    if (f_ != nullptr) std::fclose(f_);
  }

 private:
  std::string path_;
  bool with_gps_;
  std::FILE* f_ = nullptr;
};

inline void printCounters(const core::EstimatorCounters& c, std::size_t rows, double seconds) {
  std::fprintf(stderr, "{\"rows\":%zu", rows);
  core::forEachCounter(c, [](const char* name, std::uint64_t v) {
    std::fprintf(stderr, ",\"%s\":%llu", name, static_cast<unsigned long long>(v));
  });
  std::fprintf(stderr, ",\"estimator_ns_per_sample\":%.1f}\n", rows ? seconds * 1e9 / rows : 0.0);
}

}  // namespace headingd::replay
