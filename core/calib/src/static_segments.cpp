#include "headingd/calib/static_segments.hpp"

#include <algorithm>
#include <cmath>

#include "headingd/calib/calibration_error.hpp"

namespace headingd::calib {

namespace {

using core::Vec3;

bool finite(const core::ImuSample& s) { return s.gyro_rad_s.allFinite() && s.accel_m_s2.allFinite(); }

}  // namespace

double sampleRateHz(std::span<const core::ImuSample> samples) {
  std::vector<std::int64_t> steps;
  for (std::size_t i = 1; i < samples.size() && steps.size() < 5000; ++i) {
    steps.push_back(samples[i].t_ns - samples[i - 1].t_ns);
  }
  if (steps.empty()) throw CalibrationError("too few samples to tell the sample rate");
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  const std::int64_t median = steps[steps.size() / 2];
  if (median <= 0) throw CalibrationError("timestamps do not increase: cannot tell the sample rate");
  return 1e9 / static_cast<double>(median);
}

StaticSegment summarise(std::span<const core::ImuSample> samples, std::size_t begin, std::size_t end) {
  StaticSegment seg;
  seg.begin = begin;
  seg.end = end;
  const double n = static_cast<double>(end - begin);
  if (end <= begin) return seg;
  Vec3 g2 = Vec3::Zero(), a2 = Vec3::Zero(), m2 = Vec3::Zero();
  for (std::size_t i = begin; i < end; ++i) {
    seg.gyro_mean += samples[i].gyro_rad_s;
    seg.accel_mean += samples[i].accel_m_s2;
    seg.mag_mean += samples[i].mag_uT;
  }
  seg.gyro_mean /= n;
  seg.accel_mean /= n;
  seg.mag_mean /= n;
  for (std::size_t i = begin; i < end; ++i) {
    g2 += (samples[i].gyro_rad_s - seg.gyro_mean).cwiseAbs2();
    a2 += (samples[i].accel_m_s2 - seg.accel_mean).cwiseAbs2();
    m2 += (samples[i].mag_uT - seg.mag_mean).cwiseAbs2();
  }
  const double dof = std::max(1.0, n - 1.0);
  seg.gyro_sigma = (g2 / dof).cwiseSqrt();
  seg.accel_sigma = (a2 / dof).cwiseSqrt();
  seg.mag_sigma = (m2 / dof).cwiseSqrt();
  return seg;
}

std::vector<StaticSegment> findStaticSegments(std::span<const core::ImuSample> samples, const StaticDetectionOptions& o,
                                              double rate_hz) {
  const std::size_t n = samples.size();
  if (n < 3) return {};
  if (!(rate_hz > 0.0)) rate_hz = sampleRateHz(samples);
  const auto half = static_cast<std::size_t>(std::max(1.0, std::round(0.5 * o.window_s * rate_hz)));
  // Prefix sums of values and squares: window statistics in O(1) each.
  std::vector<Vec3> sg(n + 1, Vec3::Zero()), sg2(n + 1, Vec3::Zero()), sa(n + 1, Vec3::Zero()),
      sa2(n + 1, Vec3::Zero());
  std::vector<std::size_t> bad(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool ok = finite(samples[i]);
    const Vec3 g = ok ? samples[i].gyro_rad_s : Vec3::Zero();
    const Vec3 a = ok ? samples[i].accel_m_s2 : Vec3::Zero();
    sg[i + 1] = sg[i] + g;
    sg2[i + 1] = sg2[i] + g.cwiseAbs2();
    sa[i + 1] = sa[i] + a;
    sa2[i + 1] = sa2[i] + a.cwiseAbs2();
    bad[i + 1] = bad[i] + (ok ? 0 : 1);
  }
  struct WindowStats {
    double gyro_sigma, accel_sigma, gyro_mean;
    bool valid;
  };
  std::vector<WindowStats> w(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t b = i >= half ? i - half : 0, e = std::min(n, i + half + 1);
    const double m = static_cast<double>(e - b);
    const Vec3 gm = (sg[e] - sg[b]) / m, am = (sa[e] - sa[b]) / m;
    const Vec3 gv = ((sg2[e] - sg2[b]) / m - gm.cwiseAbs2()).cwiseMax(0.0);
    const Vec3 av = ((sa2[e] - sa2[b]) / m - am.cwiseAbs2()).cwiseMax(0.0);
    // The largest axis σ: still means still on every axis.
    w[i] = {std::sqrt(gv.maxCoeff()), std::sqrt(av.maxCoeff()), gm.norm(), bad[e] == bad[b] && e - b > 2};
  }
  // Noise floor: the 5th percentile of window σ (a recording has some rest in it).
  const auto floorOf = [&](auto member) {
    std::vector<double> v;
    for (const auto& s : w) {
      if (s.valid) v.push_back(s.*member);
    }
    if (v.empty()) return 0.0;
    const std::size_t k = v.size() / 20;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
  };
  const double gyro_threshold =
      std::max(o.min_gyro_sigma_rad_s, o.noise_floor_factor * floorOf(&WindowStats::gyro_sigma));
  const double accel_threshold =
      std::max(o.min_accel_sigma_m_s2, o.noise_floor_factor * floorOf(&WindowStats::accel_sigma));
  const auto min_len = static_cast<std::size_t>(std::ceil(o.min_duration_s * rate_hz));

  std::vector<StaticSegment> out;
  std::size_t start = n;
  for (std::size_t i = 0; i <= n; ++i) {
    const bool still = i < n && w[i].valid && w[i].gyro_sigma < gyro_threshold && w[i].accel_sigma < accel_threshold &&
                       w[i].gyro_mean < o.max_gyro_mean_rad_s;
    if (still && start == n) start = i;
    if (!still && start != n) {
      if (i - start >= min_len) out.push_back(summarise(samples, start, i));
      start = n;
    }
  }
  return out;
}

}  // namespace headingd::calib
