#include "headingd/study/reference_delay.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace headingd::study {
namespace {

using core::Vec3;

double seconds(const Recording& r, std::size_t i) { return 1e-9 * static_cast<double>(r.samples[i].t_ns); }

// A member of every sample (the field, the rate) at time t, linear between samples; NaN
// outside the recording.
template <typename Get>
Vec3 interpolate(const Recording& r, double t, Get get) {
  const double t0 = seconds(r, 0), t1 = seconds(r, r.size() - 1);
  if (!(t >= t0 && t <= t1)) return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  // Uniform enough to find the neighbours from the mean period, then step to them.
  auto i = static_cast<std::size_t>((t - t0) / (t1 - t0) * static_cast<double>(r.size() - 1));
  while (i > 0 && seconds(r, i) > t) --i;
  while (i + 1 < r.size() && seconds(r, i + 1) <= t) ++i;
  if (i + 1 >= r.size()) return get(r.samples[i]);
  const double w = (t - seconds(r, i)) / (seconds(r, i + 1) - seconds(r, i));
  return (1.0 - w) * get(r.samples[i]) + w * get(r.samples[i + 1]);
}

// RMS of the field in the earth frame after its centred moving mean over `window` samples is
// taken out; samples without a reference or a field are skipped (and break the windows).
double fieldSpread(const Recording& r, double delay_s, std::size_t window) {
  std::vector<Vec3> earth(r.size(), Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!hasTruth(r.truth_nb[i])) continue;
    const Vec3 m = interpolate(r, seconds(r, i) + delay_s, [](const core::ImuSample& s) { return s.mag_uT; });
    if (m.allFinite()) earth[i] = r.truth_nb[i] * m;
  }
  // Prefix sums of the field and of how many samples have one: a window is used only whole.
  std::vector<Vec3> sums(r.size() + 1, Vec3::Zero());
  std::vector<std::size_t> counts(r.size() + 1, 0);
  for (std::size_t i = 0; i < r.size(); ++i) {
    const bool known = earth[i].allFinite();
    sums[i + 1] = sums[i] + (known ? earth[i] : Vec3::Zero());
    counts[i + 1] = counts[i] + (known ? 1 : 0);
  }
  const std::size_t half = window / 2;
  double sum_sq = 0.0;
  std::size_t n = 0;
  for (std::size_t i = half; i + half < r.size(); ++i) {
    const std::size_t lo = i - half, hi = i + half + 1;
    if (counts[hi] - counts[lo] != hi - lo) continue;
    sum_sq += (earth[i] - (sums[hi] - sums[lo]) / static_cast<double>(hi - lo)).squaredNorm();
    ++n;
  }
  return n > 0 ? std::sqrt(sum_sq / static_cast<double>(n)) : std::numeric_limits<double>::quiet_NaN();
}

// RMS difference between the gyro shifted by shift_s and the reference's rate.
double rateMismatch(const Recording& r, double shift_s) {
  double sum_sq = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i + 1 < r.size(); ++i) {
    const Vec3 reference = referenceRate(r, i);
    if (!reference.allFinite() || reference.norm() > 20.0) continue;  // unknown, or a marker swap
    const double mid = 0.5 * (seconds(r, i) + seconds(r, i + 1));
    const Vec3 gyro = interpolate(r, mid + shift_s, [](const core::ImuSample& s) { return s.gyro_rad_s; });
    if (!gyro.allFinite()) continue;
    sum_sq += (gyro - reference).squaredNorm();
    ++n;
  }
  return n > 0 ? std::sqrt(sum_sq / static_cast<double>(n)) : std::numeric_limits<double>::quiet_NaN();
}

template <typename Cost>
double bestOf(double min_s, double max_s, Cost cost, double* best_cost = nullptr) {
  double best = std::numeric_limits<double>::quiet_NaN(), lowest = std::numeric_limits<double>::infinity();
  for (int ms = static_cast<int>(std::lround(1e3 * min_s)); ms <= static_cast<int>(std::lround(1e3 * max_s)); ++ms) {
    const double c = cost(1e-3 * ms);
    if (c < lowest) {
      lowest = c;
      best = 1e-3 * ms;
    }
  }
  if (best_cost) *best_cost = lowest;
  return best;
}

}  // namespace

ReferenceDelays measureReferenceDelays(const Recording& r, double min_s, double max_s) {
  ReferenceDelays d;
  if (r.size() < 100 || !(r.rate_hz > 0.0)) return d;
  // A 0.5 s moving mean: longer than a stride's turn, shorter than the walk from one part of a
  // room's field to another.
  const auto window = static_cast<std::size_t>(0.5 * r.rate_hz) | 1U;
  d.mag_s = bestOf(
      min_s, max_s, [&](double s) { return fieldSpread(r, s, window); }, &d.mag_spread_uT);
  d.mag_spread_at_zero_uT = fieldSpread(r, 0.0, window);
  d.gyro_s = bestOf(-0.02, 0.02, [&](double s) { return rateMismatch(r, s); });
  d.valid = std::isfinite(d.mag_s) && std::isfinite(d.gyro_s);
  return d;
}

}  // namespace headingd::study
