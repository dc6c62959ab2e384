#include "headingd/calib/ellipsoid_fit.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace headingd::calib {

namespace {

using core::Mat3;
using core::Vec3;
using Vec10 = Eigen::Matrix<double, 10, 1>;

std::string format(const char* fmt, double a, double b = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

// One row of M (Kok & Schön eq. 22) for the symmetric A: the coefficients of
// (a11, a22, a33, a12, a13, a23, b1, b2, b3, c) in yᵀAy + bᵀy + c.
Vec10 quadricRow(const Vec3& y) {
  Vec10 r;
  r << y.x() * y.x(), y.y() * y.y(), y.z() * y.z(), 2.0 * y.x() * y.y(), 2.0 * y.x() * y.z(), 2.0 * y.y() * y.z(),
      y.x(), y.y(), y.z(), 1.0;
  return r;
}

struct Quadric {
  Mat3 a;
  Vec3 b;
  double c;
};

Quadric unpack(const Vec10& xi) {
  Quadric q;
  q.a << xi(0), xi(3), xi(4), xi(3), xi(1), xi(5), xi(4), xi(5), xi(2);
  q.b = xi.segment<3>(6);
  q.c = xi(9);
  return q;
}

bool positiveDefinite(const Mat3& a) {
  const Eigen::SelfAdjointEigenSolver<Mat3> es(a);
  return es.info() == Eigen::Success && es.eigenvalues().minCoeff() > 0.0;
}

// Eq. 23 without the cone: min ½|Mξ|² subject to Tr A = 1, an equality-constrained linear
// least-squares problem (a33 = 1 - a11 - a22 substituted). Its solution is the SDP's when
// the A it gives is positive definite.
//
// `sphere_weight` adds ½ w n |A - I/3|² (Frobenius): a pull towards a sphere in the
// normalised coordinates, used only when the plain fit is implausible (plausibleQuadric).
Vec10 traceConstrainedFit(const Eigen::MatrixXd& m, double sphere_weight) {
  // Columns for (a11, a22, a12, a13, a23, b, c) after substitution.
  const Eigen::Index n = m.rows();
  const Eigen::Index extra = sphere_weight > 0.0 ? 6 : 0;
  Eigen::MatrixXd reduced = Eigen::MatrixXd::Zero(n + extra, 9);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + extra);
  reduced.block(0, 0, n, 1) = m.col(0) - m.col(2);
  reduced.block(0, 1, n, 1) = m.col(1) - m.col(2);
  reduced.block(0, 2, n, 7) = m.rightCols(7);
  rhs.head(n) = -m.col(2);
  if (extra > 0) {
    const double s = std::sqrt(sphere_weight * static_cast<double>(n));
    // a11 - 1/3, a22 - 1/3, a33 - 1/3 = 2/3 - a11 - a22, √2 a12, √2 a13, √2 a23.
    reduced(n, 0) = s, rhs(n) = s / 3.0;
    reduced(n + 1, 1) = s, rhs(n + 1) = s / 3.0;
    reduced(n + 2, 0) = -s, reduced(n + 2, 1) = -s, rhs(n + 2) = -2.0 * s / 3.0;
    reduced(n + 3, 2) = std::sqrt(2.0) * s;
    reduced(n + 4, 3) = std::sqrt(2.0) * s;
    reduced(n + 5, 4) = std::sqrt(2.0) * s;
  }
  const Eigen::VectorXd x = reduced.colPivHouseholderQr().solve(rhs);
  Vec10 xi;
  xi << x(0), x(1), 1.0 - x(0) - x(1), x.segment<7>(2);
  return xi;
}

// An ellipsoid a magnetometer can give, in the normalised coordinates (data centred, unit RMS
// radius): A positive definite with axes no more than 6 to 1 (Table 2's scales 0.5-1.5 with
// 30° skews reach about 4), centre within three radii of the data's centroid.
bool plausibleQuadric(const Quadric& q) {
  if (!q.a.allFinite() || !q.b.allFinite()) return false;
  const Eigen::SelfAdjointEigenSolver<Mat3> es(q.a);
  if (es.info() != Eigen::Success || !(es.eigenvalues().minCoeff() > 0.0)) return false;
  if (es.eigenvalues().maxCoeff() > 36.0 * es.eigenvalues().minCoeff()) return false;
  const Vec3 centre = -0.5 * q.a.inverse() * q.b;
  return centre.norm() < 3.0;
}

// The same algebraic cost on the positive-definite cone: A = L Lᵀ / Tr(L Lᵀ), L lower
// triangular, so Tr A = 1 and A is positive semidefinite by construction (the SDP's
// feasible set, written so that Ceres can search it).
struct ConeAlgebraicResidual {
  explicit ConeAlgebraicResidual(const Vec10& row) : row_(row) {}
  template <typename T>
  bool operator()(const T* l, const T* bc, T* residual) const {
    // l = (l11, l21, l22, l31, l32, l33)
    const T a11 = l[0] * l[0];
    const T a12 = l[0] * l[1];
    const T a13 = l[0] * l[3];
    const T a22 = l[1] * l[1] + l[2] * l[2];
    const T a23 = l[1] * l[3] + l[2] * l[4];
    const T a33 = l[3] * l[3] + l[4] * l[4] + l[5] * l[5];
    const T trace = a11 + a22 + a33;
    const T quad =
        (row_(0) * a11 + row_(1) * a22 + row_(2) * a33 + row_(3) * a12 + row_(4) * a13 + row_(5) * a23) / trace;
    residual[0] = quad + row_(6) * bc[0] + row_(7) * bc[1] + row_(8) * bc[2] + row_(9) * bc[3];
    return true;
  }
  Vec10 row_;
};

Vec10 coneConstrainedFit(const std::vector<Vec10>& rows, const Vec10& start) {
  // Start from the positive part of the unconstrained solution.
  const Quadric q = unpack(start);
  Eigen::SelfAdjointEigenSolver<Mat3> es(q.a);
  Vec3 ev = es.eigenvalues().cwiseMax(1e-3 * std::max(1e-12, es.eigenvalues().cwiseAbs().maxCoeff()));
  Mat3 a0 = es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
  a0 /= a0.trace();
  const Mat3 l0 = a0.llt().matrixL();
  std::array<double, 6> l{l0(0, 0), l0(1, 0), l0(1, 1), l0(2, 0), l0(2, 1), l0(2, 2)};
  std::array<double, 4> bc{q.b.x(), q.b.y(), q.b.z(), q.c};
  ceres::Problem problem;
  for (const Vec10& row : rows) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<ConeAlgebraicResidual, 1, 6, 4>(new ConeAlgebraicResidual(row)), nullptr,
        l.data(), bc.data());
  }
  ceres::Solver::Options options;
  options.max_num_iterations = 200;
  options.linear_solver_type = ceres::DENSE_QR;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  Mat3 lm = Mat3::Zero();
  lm(0, 0) = l[0];
  lm(1, 0) = l[1];
  lm(1, 1) = l[2];
  lm(2, 0) = l[3];
  lm(2, 1) = l[4];
  lm(2, 2) = l[5];
  Mat3 a = lm * lm.transpose();
  a /= a.trace();
  Vec10 xi;
  xi << a(0, 0), a(1, 1), a(2, 2), a(0, 1), a(0, 2), a(1, 2), bc[0], bc[1], bc[2], bc[3];
  return xi;
}

// Geometric refinement: the calibrated field m = W (y - o), W = D⁻¹ upper triangular (any
// invertible W gives a positive-definite WᵀW), residual |m| - 1 on the normalised sphere.
// The algebraic cost weights points by their distance from the centre; this one is the
// error in µT a user sees in the field norm.
struct SphereResidual {
  explicit SphereResidual(const Vec3& y) : y_(y) {}
  template <typename T>
  bool operator()(const T* w, const T* o, T* residual) const {
    const T d0 = T(y_.x()) - o[0], d1 = T(y_.y()) - o[1], d2 = T(y_.z()) - o[2];
    const T m0 = w[0] * d0 + w[1] * d1 + w[2] * d2;
    const T m1 = w[3] * d1 + w[4] * d2;
    const T m2 = w[5] * d2;
    residual[0] = ceres::sqrt(m0 * m0 + m1 * m1 + m2 * m2 + T(1e-30)) - T(1.0);
    return true;
  }
  Vec3 y_;
};

Mat3 symmetricRoot(const Mat3& spd) {
  const Eigen::SelfAdjointEigenSolver<Mat3> es(spd);
  return es.eigenvectors() * es.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() * es.eigenvectors().transpose();
}

const std::vector<Vec3>& fibonacciCells() {
  static const std::vector<Vec3> cells = [] {
    constexpr int kCells = 200;
    std::vector<Vec3> c;
    c.reserve(kCells);
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kCells; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / kCells;
      const double r = std::sqrt(1.0 - z * z);
      c.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return c;
  }();
  return cells;
}

}  // namespace

double sphereCoverage(std::span<const Vec3> directions) {
  const auto& cells = fibonacciCells();
  std::vector<bool> hit(cells.size(), false);
  for (const Vec3& d : directions) {
    const double n = d.norm();
    if (!(n > 0.0) || !std::isfinite(n)) continue;
    const Vec3 u = d / n;
    std::size_t best = 0;
    double best_dot = -2.0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const double dot = cells[i].dot(u);
      if (dot > best_dot) {
        best_dot = dot;
        best = i;
      }
    }
    hit[best] = true;
  }
  std::size_t count = 0;
  for (const bool h : hit) count += h ? 1 : 0;
  return static_cast<double>(count) / static_cast<double>(cells.size());
}

EllipsoidFit fitEllipsoid(std::span<const Vec3> mag_uT, double field_norm_uT, const EllipsoidFitOptions& options) {
  if (!(field_norm_uT > 0.0) || !std::isfinite(field_norm_uT)) {
    throw CalibrationError(
        format("ellipsoid fit: the field norm must be positive and finite (got %g uT)", field_norm_uT));
  }
  const auto n = mag_uT.size();
  if (n < static_cast<std::size_t>(std::max(10, options.min_samples))) {
    throw CalibrationError(format("ellipsoid fit: %g magnetometer samples, at least %g needed", static_cast<double>(n),
                                  static_cast<double>(std::max(10, options.min_samples))));
  }
  Vec3 centre = Vec3::Zero();
  for (const Vec3& y : mag_uT) {
    if (!y.allFinite()) throw CalibrationError("ellipsoid fit: a magnetometer sample is not finite");
    centre += y;
  }
  centre /= static_cast<double>(n);
  double spread = 0.0;
  for (const Vec3& y : mag_uT) spread += (y - centre).squaredNorm();
  spread = std::sqrt(spread / static_cast<double>(n));
  if (!(spread > 1e-9 * std::max(1.0, centre.norm()))) {
    throw CalibrationError("ellipsoid fit: the magnetometer did not change at all (no rotation); coverage 0.000");
  }

  // Work on normalised data (centred, unit RMS radius) so M is well conditioned.
  std::vector<Vec3> z(n);
  std::vector<Vec10> rows(n);
  Eigen::MatrixXd m(static_cast<Eigen::Index>(n), 10);
  for (std::size_t i = 0; i < n; ++i) {
    z[i] = (mag_uT[i] - centre) / spread;
    rows[i] = quadricRow(z[i]);
    m.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  }
  // Raw coverage, for the message when no ellipsoid can be fitted at all.
  const double raw_coverage = sphereCoverage(z);

  // Data that cover only a band of the sphere (K&S §8's 3 s of turns leave one spread at
  // about 0.15 of the field) with noise of a few percent of the field leave the quadric
  // nearly free across the band: the plain fit (eq. 23) can then pick a flat ellipsoid
  // thousands of µT across that passes through the band with almost no residual (3 of 30
  // K&S runs). Then pull towards a sphere, as little as gives a plausible ellipsoid.
  Vec10 xi = traceConstrainedFit(m, 0.0);
  for (const double pull : {0.1, 1.0, 10.0}) {
    if (options.sphere_weight <= 0.0 || plausibleQuadric(unpack(xi))) break;
    xi = traceConstrainedFit(m, pull * options.sphere_weight);
  }
  Quadric q = unpack(xi);
  if (!xi.allFinite() || !positiveDefinite(q.a)) {
    if (!xi.allFinite()) xi = Vec10::Zero(), xi(0) = xi(1) = xi(2) = 1.0 / 3.0, xi(9) = -1.0 / 3.0;
    xi = coneConstrainedFit(rows, xi);
    q = unpack(xi);
  }
  // Kok & Schön eq. 24 (with o = -½ A⁻¹ b, which follows from eq. 20b).
  const Mat3 a_inv = q.a.inverse();
  const double beta_inv = 0.25 * q.b.dot(a_inv * q.b) - q.c;
  if (!positiveDefinite(q.a) || !(beta_inv > 0.0) || !std::isfinite(beta_inv)) {
    throw CalibrationError(format(
        "ellipsoid fit: no ellipsoid fits the magnetometer data: the rotations cover %.0f %% of the sphere; turn "
        "the sensor through all directions (every face up and down)",
        100.0 * raw_coverage));
  }
  Vec3 o = -0.5 * a_inv * q.b;
  // Normalised units: (z - o)ᵀ (A/β⁻¹) (z - o) = 1, so W = chol(A / β⁻¹)ᵀ maps to the unit sphere.
  Mat3 w = (q.a / beta_inv).llt().matrixU();

  // The geometric problem: refined if asked, and its Jacobian at the answer gives the
  // condition figure (ratio of extreme singular values, normalised units).
  std::array<double, 6> wp{w(0, 0), w(0, 1), w(0, 2), w(1, 1), w(1, 2), w(2, 2)};
  std::array<double, 3> op{o.x(), o.y(), o.z()};
  ceres::Problem problem;
  for (const Vec3& zi : z) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SphereResidual, 1, 6, 3>(new SphereResidual(zi)), nullptr,
                             wp.data(), op.data());
  }
  if (options.geometric_refinement) {
    ceres::Solver::Options so;
    so.max_num_iterations = 100;
    so.linear_solver_type = ceres::DENSE_QR;
    so.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    Mat3 wr = Mat3::Zero();
    wr(0, 0) = wp[0], wr(0, 1) = wp[1], wr(0, 2) = wp[2], wr(1, 1) = wp[3], wr(1, 2) = wp[4], wr(2, 2) = wp[5];
    const Vec3 orr(op[0], op[1], op[2]);
    // With little rotation the refinement can slide into a degenerate solution (a far
    // centre, a nearly singular W that squashes the points onto a band of the sphere):
    // keep it only if it stays about as well conditioned as the algebraic fit.
    const auto condition = [](const Mat3& m) {
      const Eigen::JacobiSVD<Mat3> svd(m);
      return svd.singularValues()(0) / std::max(1e-300, svd.singularValues()(2));
    };
    Quadric refined;
    refined.a = wr.transpose() * wr;
    refined.b = -2.0 * refined.a * orr;
    refined.c = 0.0;  // the centre and the axes are what plausibleQuadric reads
    if (summary.IsSolutionUsable() && wr.allFinite() && orr.allFinite() && std::abs(wr.determinant()) > 1e-12 &&
        condition(wr) < 2.0 * condition(w) + 1.0 && plausibleQuadric(refined)) {
      w = wr;
      o = orr;
    } else {
      wp = {w(0, 0), w(0, 1), w(0, 2), w(1, 1), w(1, 2), w(2, 2)};
      op = {o.x(), o.y(), o.z()};
    }
  }
  double condition_number = std::numeric_limits<double>::infinity();
  {
    ceres::CRSMatrix jacobian;
    if (problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &jacobian)) {
      Eigen::MatrixXd j = Eigen::MatrixXd::Zero(jacobian.num_rows, jacobian.num_cols);
      for (int r = 0; r < jacobian.num_rows; ++r) {
        for (int k = jacobian.rows[static_cast<std::size_t>(r)]; k < jacobian.rows[static_cast<std::size_t>(r) + 1];
             ++k) {
          j(r, jacobian.cols[static_cast<std::size_t>(k)]) = jacobian.values[static_cast<std::size_t>(k)];
        }
      }
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j);
      const auto& sv = svd.singularValues();
      if (sv.size() > 0 && sv(sv.size() - 1) > 0.0) condition_number = sv(0) / sv(sv.size() - 1);
    }
  }

  // Back to µT: m_uT = F · W (y - centre)/spread - ..., so D⁻¹ = F W / spread, o_uT = centre + spread o.
  const Mat3 d_inv_upper = field_norm_uT * w / spread;
  // D is fixed only up to a rotation (eq. 25); take the symmetric root of D Dᵀ, the one
  // that adds no rotation to the soft iron (the misalignment step finds the rest).
  const Mat3 ddt = (d_inv_upper.transpose() * d_inv_upper).inverse();
  EllipsoidFit fit;
  fit.D = symmetricRoot(0.5 * (ddt + ddt.transpose()));
  fit.offset_uT = centre + spread * o;
  fit.field_norm_uT = field_norm_uT;
  fit.condition_number = condition_number;
  const Mat3 d_inv = fit.D.inverse();
  std::vector<Vec3> directions(n);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    directions[i] = d_inv * (mag_uT[i] - fit.offset_uT);
    const double e = directions[i].norm() - field_norm_uT;
    sum2 += e * e;
  }
  fit.residual_rms_uT = std::sqrt(sum2 / static_cast<double>(n));
  fit.coverage = sphereCoverage(directions);
  // Data that hardly moved (a sensor at rest) fit a tiny "ellipsoid" of noise. A rotation
  // spreads the data in at least two directions (K&S §8's short turns leave the third spread
  // at about 0.15 of the field, below the noise of Table 2's worst magnetometer), so the
  // middle spread of the raw data must stand well above the noise. The noise comes from
  // sample-to-sample differences (median, so turns between samples hardly count) where
  // that is smaller than the fit's residual, which a poor fit of noisy data inflates.
  {
    Mat3 cov = Mat3::Zero();
    for (const Vec3& y : mag_uT) cov += (y - centre) * (y - centre).transpose();
    cov /= static_cast<double>(n);
    const double middle = std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Mat3>(cov).eigenvalues()(1)));
    std::vector<double> step2(n - 1);
    for (std::size_t i = 1; i < n; ++i) step2[i - 1] = (mag_uT[i] - mag_uT[i - 1]).squaredNorm();
    std::nth_element(step2.begin(), step2.begin() + static_cast<std::ptrdiff_t>(step2.size() / 2), step2.end());
    // |y_k - y_{k-1}|² of pure noise is 2·3σ² on average; its median about 0.79 of that.
    // Data not in time order (a test lattice) make the differences large: then the fit's
    // residual bounds the noise.
    const double noise = std::min(std::sqrt(step2[step2.size() / 2] / (6.0 * 0.79)), fit.residual_rms_uT);
    if (middle < 2.0 * noise) {
      throw CalibrationError(format(
          "ellipsoid fit: the magnetometer hardly moved: its spread across the second direction is %.2f uT against "
          "%.2f uT of noise; turn the sensor through all directions (every face up and down)",
          middle, noise));
    }
  }
  // A fit that squashes well-spread data into a small patch is degenerate: the points are
  // not one ellipsoid (say a magnet was attached part-way through).
  const bool degenerate = fit.coverage < options.min_coverage && raw_coverage >= options.min_coverage;
  if (!fit.D.allFinite() || !fit.offset_uT.allFinite() || !std::isfinite(fit.residual_rms_uT) || degenerate) {
    throw CalibrationError(format(
        "ellipsoid fit: the data do not lie on one ellipsoid (the rotations cover %.0f %% of the sphere); is the "
        "distortion constant over the recording (a magnet attached or removed part-way)?",
        100.0 * raw_coverage));
  }
  if (fit.coverage < options.min_coverage) {
    throw CalibrationError(format(
        "ellipsoid fit: the rotations cover only %.0f %% of the sphere (at least %.0f %% needed); turn the sensor "
        "through all directions (every face up and down)",
        100.0 * fit.coverage, 100.0 * options.min_coverage));
  }
  return fit;
}

}  // namespace headingd::calib
