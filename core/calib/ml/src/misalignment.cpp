#include "headingd/calib/ml/misalignment.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/core/angles.hpp"

namespace headingd::calib {

namespace {

using core::Mat3;
using core::Vec3;
using Vec4d = Eigen::Matrix<double, 4, 1>;
using Mat4d = Eigen::Matrix<double, 4, 4>;

double cost(const Mat3& r_dt, double mz, std::span<const Vec3> u, std::span<const Vec3> v) {
  double c = 0.0;
  for (std::size_t t = 0; t < u.size(); ++t) {
    const double r = mz - v[t].dot(r_dt * u[t]);
    c += r * r;
  }
  return 0.5 * c;
}

// The 24 proper rotations of the cube: every signed permutation matrix with det +1.
std::vector<Mat3> cubeRotations() {
  std::vector<Mat3> out;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms) {
    for (int signs = 0; signs < 8; ++signs) {
      Mat3 m = Mat3::Zero();
      for (int r = 0; r < 3; ++r) m(r, p[r]) = (signs >> r) & 1 ? -1.0 : 1.0;
      if (m.determinant() > 0.0) out.push_back(m);
    }
  }
  return out;
}

struct Solution {
  Mat3 r_dt;  // R_Dᵀ
  double mz;
  double cost;
  int iterations;
};

Solution gaussNewton(Mat3 r_dt, std::span<const Vec3> u, std::span<const Vec3> v) {
  // m_z that is optimal for the start: the mean inner product.
  double mz = 0.0;
  for (std::size_t t = 0; t < u.size(); ++t) mz += v[t].dot(r_dt * u[t]);
  mz /= static_cast<double>(u.size());
  double c = cost(r_dt, mz, u, v);
  int it = 0;
  for (; it < 50; ++it) {
    Mat4d jtj = Mat4d::Zero();
    Vec4d jtr = Vec4d::Zero();
    for (std::size_t t = 0; t < u.size(); ++t) {
      const Vec3 w = r_dt * u[t];
      const double r = mz - v[t].dot(w);
      Vec4d j;
      j.head<3>() = -w.cross(v[t]);  // ∂r/∂φ for w ← w + φ × w
      j(3) = 1.0;
      jtj += j * j.transpose();
      jtr += j * r;
    }
    const Vec4d step = -(jtj + 1e-9 * Mat4d::Identity()).ldlt().solve(jtr);
    // Halve the step until the cost drops (a plain line search keeps GN from overshooting).
    double alpha = 1.0;
    bool improved = false;
    for (int k = 0; k < 20; ++k, alpha *= 0.5) {
      const Vec3 phi = alpha * step.head<3>();
      const double angle = phi.norm();
      const Mat3 dr = angle > 0.0 ? Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix() : Mat3::Identity();
      const Mat3 trial = dr * r_dt;
      const double trial_mz = mz + alpha * step(3);
      const double trial_cost = cost(trial, trial_mz, u, v);
      if (trial_cost < c) {
        const double gain = c - trial_cost;
        r_dt = trial;
        mz = trial_mz;
        c = trial_cost;
        improved = true;
        if (gain < 1e-12 * (1.0 + c)) it = 1000;  // converged
        break;
      }
    }
    if (!improved || it >= 1000) break;
  }
  return {r_dt, mz, c, std::min(it, 50)};
}

}  // namespace

std::vector<MisalignmentEstimate> misalignmentMinima(std::span<const Vec3> mag_on_sphere,
                                                     std::span<const Vec3> vertical_body) {
  if (mag_on_sphere.size() != vertical_body.size()) {
    throw CalibrationError("misalignment: magnetometer and vertical sequences differ in length");
  }
  if (mag_on_sphere.size() < 10) {
    throw CalibrationError("misalignment: fewer than 10 samples");
  }
  std::vector<Solution> found;
  for (const Mat3& start : cubeRotations()) {
    const Solution s = gaussNewton(start, mag_on_sphere, vertical_body);
    if (std::isfinite(s.cost) && std::abs(s.mz) <= 1.0) found.push_back(s);
  }
  std::stable_sort(found.begin(), found.end(), [](const Solution& a, const Solution& b) { return a.cost < b.cost; });
  // Several starts descend into the same minimum: keep the lowest of each group.
  constexpr double kSameMinimum_rad = 5.0 * core::kRadPerDeg;
  std::vector<MisalignmentEstimate> out;
  std::vector<Mat3> kept;
  for (const Solution& s : found) {
    const bool seen = std::any_of(kept.begin(), kept.end(), [&](const Mat3& r) {
      return Eigen::AngleAxisd(r.transpose() * s.r_dt).angle() < kSameMinimum_rad;
    });
    if (seen) continue;
    kept.push_back(s.r_dt);
    MisalignmentEstimate e;
    e.rotation = s.r_dt.transpose();
    e.field_down = s.mz;
    e.dip_rad = std::asin(std::clamp(s.mz, -1.0, 1.0));
    e.rms_residual = std::sqrt(2.0 * s.cost / static_cast<double>(mag_on_sphere.size()));
    e.iterations = s.iterations;
    out.push_back(e);
  }
  if (out.empty()) {  // no start kept |m_z| <= 1: the identity, as before any search
    MisalignmentEstimate e;
    e.rms_residual = std::sqrt(2.0 * cost(Mat3::Identity(), 0.0, mag_on_sphere, vertical_body) /
                               static_cast<double>(mag_on_sphere.size()));
    out.push_back(e);
  }
  return out;
}

MisalignmentEstimate estimateMisalignment(std::span<const Vec3> mag_on_sphere, std::span<const Vec3> vertical_body,
                                          DipSign expected) {
  const std::vector<MisalignmentEstimate> minima = misalignmentMinima(mag_on_sphere, vertical_body);
  if (expected != DipSign::kUnknown) {
    for (const MisalignmentEstimate& m : minima) {
      if (dipAgrees(m.field_down, expected)) return m;
    }
  }
  return minima.front();
}

}  // namespace headingd::calib
