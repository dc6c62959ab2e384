#include "headingd/study/scoring.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace headingd::study {

namespace {

using core::Quat;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

bool usable(const Recording& r, const std::vector<Quat>& est, std::size_t i) {
  return r.moving[i] && hasTruth(r.truth_nb[i]) && hasTruth(est[i]);
}

// The rotation whose quaternion is closest to all of qs (largest eigenvector of Σ q qᵀ;
// Markley, Cheng, Crassidis, Oshman 2007): sign-free, so q and -q count the same.
Quat quaternionMean(const std::vector<Quat>& qs) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  for (const Quat& q : qs) m += q.coeffs() * q.coeffs().transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(m);
  const Eigen::Vector4d v = eig.eigenvectors().col(3);  // eigenvalues ascend
  return Quat(v(3), v(0), v(1), v(2)).normalized();     // coeffs() is (x, y, z, w)
}

double seconds(const Recording& r, std::size_t i) {
  return 1e-9 * static_cast<double>(r.samples[i].t_ns - r.samples[0].t_ns);
}

}  // namespace

std::vector<Quat> runEstimator(const Recording& r, const core::EstimatorParams& params,
                               const EstimatorObserver& observe) {
  core::Estimator estimator(params);
  if (r.reference_field_uT > 0.0) estimator.setReferenceField(r.reference_field_uT, r.reference_inclination_rad);
  std::vector<Quat> out;
  out.reserve(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    estimator.process(r.samples[i]);
    const auto& o = estimator.output();
    out.push_back(o.valid ? o.q_nb : Quat(kNan, kNan, kNan, kNan));
    if (observe) observe(i, estimator);
  }
  return out;
}

std::vector<core::OrientationError> perSampleErrors(const Recording& r, const std::vector<Quat>& estimates) {
  std::vector<core::OrientationError> e(r.size(), {kNan, kNan, kNan});
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (hasTruth(r.truth_nb[i]) && hasTruth(estimates[i])) {
      e[i] = core::orientationError(estimates[i], core::nedToEnu(r.truth_nb[i]));
    }
  }
  return e;
}

double headingCoverage(const Recording& r, const std::vector<Quat>& estimates, const std::vector<double>& sigmas_rad,
                       double k) {
  std::size_t scored = 0, within = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!usable(r, estimates, i)) continue;
    ++scored;
    const auto e = core::orientationError(estimates[i], core::nedToEnu(r.truth_nb[i]));
    if (e.heading_rad <= k * sigmas_rad[i]) ++within;
  }
  return scored == 0 ? kNan : static_cast<double>(within) / static_cast<double>(scored);
}

std::vector<Quat> alignedEstimates(const Recording& r, const std::vector<Quat>& estimates) {
  Quat q_e = Quat::Identity(), q_b = Quat::Identity();
  std::vector<Quat> terms;
  for (int iteration = 0; iteration < 8; ++iteration) {
    terms.clear();
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (usable(r, estimates, i)) terms.push_back(r.truth_nb[i] * (estimates[i] * q_b).conjugate());
    }
    if (terms.empty()) return estimates;
    q_e = quaternionMean(terms);
    terms.clear();
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (usable(r, estimates, i)) terms.push_back((q_e * estimates[i]).conjugate() * r.truth_nb[i]);
    }
    q_b = quaternionMean(terms);
  }
  std::vector<Quat> aligned(estimates.size());
  for (std::size_t i = 0; i < estimates.size(); ++i) {
    aligned[i] = hasTruth(estimates[i]) ? (q_e * estimates[i] * q_b).normalized() : estimates[i];
  }
  return aligned;
}

RunScore score(const Recording& r, const std::vector<Quat>& estimates, double opening_s) {
  RunScore s;
  core::RmseAccumulator plain, aligned, opening, after_opening;
  std::int64_t first_scored_ns = 0;
  const std::vector<Quat> fitted = alignedEstimates(r, estimates);
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (!r.moving[i] || !hasTruth(r.truth_nb[i])) continue;
    if (s.scored++ == 0) first_scored_ns = r.samples[i].t_ns;
    core::RmseAccumulator& part =
        1e-9 * static_cast<double>(r.samples[i].t_ns - first_scored_ns) < opening_s ? opening : after_opening;
    if (!hasTruth(estimates[i])) {
      ++s.failed;
      const double pi = std::numbers::pi;
      plain.add({pi, pi, pi});
      aligned.add({pi, pi, pi});
      part.add({pi, pi, pi});
      continue;
    }
    const auto e = core::orientationError(estimates[i], core::nedToEnu(r.truth_nb[i]));
    plain.add(e);
    const auto e_fitted = core::orientationError(fitted[i], core::nedToEnu(r.truth_nb[i]));
    aligned.add(e_fitted);
    part.add(e_fitted);
    s.max_inclination_rad = std::max(s.max_inclination_rad, e.inclination_rad);
  }
  s.rmse = plain.rmse();
  s.aligned_rmse = aligned.rmse();
  s.aligned_opening_rmse = opening.rmse();
  s.aligned_after_opening_rmse = after_opening.rmse();
  return s;
}

EpisodeScore scoreEpisode(const Recording& r, const std::vector<Quat>& estimates, double settle_s, double settled_rad) {
  EpisodeScore s;
  std::size_t first = r.size(), last = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r.moving[i]) {
      first = std::min(first, i);
      last = i;
    }
  }
  if (first == r.size()) return s;
  s.motion_start_s = seconds(r, first);
  s.motion_end_s = seconds(r, last);
  // Samples without a truth are left out; a sample without an estimate counts as 180°.
  const double pi = std::numbers::pi;
  const auto inclination = [&](std::size_t i) {
    return hasTruth(estimates[i]) ? core::orientationError(estimates[i], core::nedToEnu(r.truth_nb[i])).inclination_rad
                                  : pi;
  };
  double sum2 = 0.0;
  std::size_t n = 0;
  for (std::size_t i = first; i <= last; ++i) {
    if (!hasTruth(r.truth_nb[i])) continue;
    const double e = inclination(i);
    sum2 += e * e;
    ++n;
    s.max_inclination_rad = std::max(s.max_inclination_rad, e);
  }
  s.inclination_rmse_rad = n ? std::sqrt(sum2 / static_cast<double>(n)) : kNan;
  bool settled_at_end = true;
  for (std::size_t i = last + 1; i < r.size(); ++i) {
    if (!hasTruth(r.truth_nb[i])) continue;
    const double since_end = seconds(r, i) - s.motion_end_s;
    const double e = inclination(i);
    if (since_end >= settle_s) s.max_inclination_after_rad = std::max(s.max_inclination_after_rad, e);
    if (e >= settled_rad) s.settle_time_s = since_end;
    settled_at_end = e < settled_rad;
  }
  if (!settled_at_end) s.settle_time_s = std::numeric_limits<double>::infinity();
  return s;
}

}  // namespace headingd::study
