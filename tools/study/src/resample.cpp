#include "headingd/study/resample.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace headingd::study {

namespace {

using core::Quat;
using core::Vec3;

// Rate that turns q_from into q_to in dt (body axes: q_to = q_from ⊗ exp(½ ω dt)).
Vec3 meanRate(const Quat& q_from, const Quat& q_to, double dt_s) {
  Quat r = q_from.conjugate() * q_to;
  if (r.w() < 0.0) r.coeffs() = -r.coeffs();
  const double s = r.vec().norm();
  const double factor = s > 1e-12 ? 2.0 * std::atan2(s, r.w()) / s : 2.0 / r.w();
  return (factor / dt_s) * r.vec();
}

// The source, seen as piecewise-constant signals: sample i holds over (t_{i-1}, t_i].
class SourceSignals {
 public:
  explicit SourceSignals(const Recording& r) : r_(r) {
    attitude_.push_back(Quat::Identity());
    for (std::size_t i = 1; i < r.size(); ++i) {
      const double dt = seconds(i) - seconds(i - 1);
      attitude_.push_back((attitude_.back() * core::gyroIncrement(r.samples[i].gyro_rad_s, dt)).normalized());
    }
  }
  double seconds(std::size_t i) const { return 1e-9 * static_cast<double>(r_.samples[i].t_ns - r_.samples[0].t_ns); }
  // Index of the source interval (t_{i-1}, t_i] that holds t (t within the recording).
  std::size_t intervalOf(double t) const {
    while (hint_ + 1 < r_.size() && seconds(hint_) < t) ++hint_;
    while (hint_ > 1 && seconds(hint_ - 1) >= t) --hint_;
    return hint_;
  }
  Quat gyroAttitude(double t) const {
    if (t <= 0.0) return attitude_[0];
    const std::size_t i = intervalOf(t);
    const double dt = t - seconds(i - 1);
    return (attitude_[i - 1] * core::gyroIncrement(r_.samples[i].gyro_rad_s, dt)).normalized();
  }
  // Mean of a vector signal over (a, b].
  template <typename Get>
  Vec3 mean(double a, double b, Get get) const {
    Vec3 sum = Vec3::Zero();
    double t = a;
    while (t < b) {
      const std::size_t i = intervalOf(std::nextafter(t, b));
      const double end = std::min(b, seconds(i));
      sum += (end - t) * get(r_.samples[i]);
      if (end <= t) break;  // past the last source sample
      t = end;
    }
    return sum / (b - a);
  }

 private:
  const Recording& r_;
  std::vector<Quat> attitude_;  // gyro-integrated, at each source sample
  mutable std::size_t hint_ = 1;
};

Quat interpolatedTruth(const Recording& r, const SourceSignals& src, double t) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t i = src.intervalOf(t);
  const Quat& a = r.truth_nb[i - 1];
  const Quat& b = r.truth_nb[i];
  if (!hasTruth(a) || !hasTruth(b)) return Quat(nan, nan, nan, nan);
  const double w = std::clamp((t - src.seconds(i - 1)) / (src.seconds(i) - src.seconds(i - 1)), 0.0, 1.0);
  return a.slerp(w, b).normalized();
}

}  // namespace

Recording resample(const Recording& source, double rate_hz, VectorWindow window) {
  if (source.size() < 2) throw std::invalid_argument("resample: the source needs at least two samples");
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw std::invalid_argument("resample: rate must be positive");
  const SourceSignals src(source);
  const double duration = src.seconds(source.size() - 1);
  const double dt = 1.0 / rate_hz;
  Recording out;
  out.name = source.name;
  out.rate_hz = rate_hz;
  const auto count = static_cast<std::size_t>(std::floor(duration * rate_hz + 1e-9)) + 1;
  for (std::size_t k = 0; k < count; ++k) {
    const double t = static_cast<double>(k) * dt;
    core::ImuSample s;
    s.t_ns = source.samples[0].t_ns + static_cast<std::int64_t>(std::llround(t * 1e9));
    if (k == 0) {
      s.gyro_rad_s = source.samples[0].gyro_rad_s;
      s.accel_m_s2 = source.samples[0].accel_m_s2;
      s.mag_uT = source.samples[0].mag_uT;
      out.truth_nb.push_back(source.truth_nb[0]);
    } else {
      const double a = t - dt;
      s.gyro_rad_s = meanRate(src.gyroAttitude(a), src.gyroAttitude(t), dt);
      const double shift = window == VectorWindow::kCentred ? std::min(0.5 * dt, duration - t) : 0.0;
      s.accel_m_s2 = src.mean(a + shift, t + shift, [](const core::ImuSample& x) { return x.accel_m_s2; });
      s.mag_uT = src.mean(a + shift, t + shift, [](const core::ImuSample& x) { return x.mag_uT; });
      out.truth_nb.push_back(interpolatedTruth(source, src, t));
    }
    s.has_mag = true;
    out.samples.push_back(s);
    const std::size_t i = src.intervalOf(t);
    const bool nearer_previous = i > 0 && t - src.seconds(i - 1) < src.seconds(i) - t;
    out.moving.push_back(source.moving[nearer_previous ? i - 1 : i]);
  }
  return out;
}

}  // namespace headingd::study
