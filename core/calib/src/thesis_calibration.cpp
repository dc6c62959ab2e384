#include "headingd/calib/thesis_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "headingd/core/angles.hpp"

namespace headingd::calib {

namespace {

using core::Mat3;
using core::Vec3;
constexpr double kPi = std::numbers::pi;

}  // namespace

std::vector<Face> findSixFaces(std::span<const StaticSegment> segments, double max_tilt_deg) {
  std::array<std::optional<Face>, 6> best;
  const double cos_max = std::cos(max_tilt_deg * core::kRadPerDeg);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Vec3& a = segments[i].accel_mean;
    const double n = a.norm();
    if (!(n > 1.0)) continue;
    int axis = 0;
    a.cwiseAbs().maxCoeff(&axis);
    if (std::abs(a(axis)) / n < cos_max) continue;  // tilted: not lying on a face
    // Specific force points up: the axis pointing down reads −g.
    const int sign = a(axis) < 0.0 ? 1 : -1;
    const std::size_t slot = static_cast<std::size_t>(axis * 2 + (sign > 0 ? 0 : 1));
    if (!best[slot] || segments[i].size() > segments[best[slot]->segment].size()) best[slot] = Face{axis, sign, i};
  }
  std::string missing;
  std::vector<Face> out;
  for (std::size_t s = 0; s < 6; ++s) {
    if (best[s]) {
      out.push_back(*best[s]);
    } else {
      missing += std::string(missing.empty() ? "" : ", ") + "xyz"[s / 2] + (s % 2 == 0 ? " down" : " up");
    }
  }
  if (!missing.empty()) {
    throw CalibrationError("six-position calibration: no static segment with " + missing + " (found " +
                           std::to_string(segments.size()) + " static segments, " + std::to_string(out.size()) +
                           " of the 6 faces)");
  }
  return out;
}

AccelSixPositionResult calibrateAccelSixPosition(std::span<const StaticSegment> segments, std::span<const Face> faces,
                                                 double gravity_m_s2) {
  AccelSixPositionResult r;
  for (int axis = 0; axis < 3; ++axis) {
    std::optional<double> up_reading, down_reading;  // reading on the axis when it points up / down
    for (const Face& f : faces) {
      if (f.axis != axis) continue;
      const double v = segments[f.segment].accel_mean(axis);
      (f.sign > 0 ? down_reading : up_reading) = v;
    }
    if (!up_reading || !down_reading) throw CalibrationError("accelerometer: axis needs a face up and a face down");
    // Eq. 2.40 on the axis: up reads +K g + b, down reads −K g + b.
    r.scale(axis) = (*up_reading - *down_reading) / (2.0 * gravity_m_s2);
    r.bias_m_s2(axis) = 0.5 * (*up_reading + *down_reading);
  }
  return r;
}

GyroBiasResult gyroBiasAtRest(std::span<const StaticSegment> segments) {
  if (segments.empty()) throw CalibrationError("gyroscope bias: no static segment in the recording");
  const StaticSegment* longest = &segments[0];
  for (const auto& s : segments) {
    if (s.size() > longest->size()) longest = &s;
  }
  return {longest->gyro_mean, longest->gyro_sigma, longest->size()};
}

GyroScaleResult gyroScaleFromTurns(std::span<const core::ImuSample> samples, std::span<const StaticSegment> segments,
                                   const Vec3& bias, double rate_hz) {
  GyroScaleResult r;
  std::array<double, 3> measured{0, 0, 0}, truth{0, 0, 0};
  const double dt = 1.0 / rate_hz;
  for (std::size_t k = 1; k < segments.size(); ++k) {
    const StaticSegment& a = segments[k - 1];
    const StaticSegment& b = segments[k];
    // Same orientation before and after: gravity and field directions agree.
    const auto angle = [](const Vec3& u, const Vec3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); };
    if (angle(a.accel_mean, b.accel_mean) > 3.0 * core::kRadPerDeg) continue;
    if (a.mag_mean.norm() > 0.0 && angle(a.mag_mean, b.mag_mean) > 5.0 * core::kRadPerDeg) continue;
    Vec3 integral = Vec3::Zero();
    for (std::size_t i = a.end; i < b.begin; ++i) integral += (samples[i].gyro_rad_s - bias) * dt;
    int axis = 0;
    integral.cwiseAbs().maxCoeff(&axis);
    const double main = std::abs(integral(axis));
    // One axis only, and at least most of a turn.
    if (main < 1.5 * kPi || main < 0.97 * integral.norm()) continue;
    const double turns = std::round(main / (2.0 * kPi));
    if (turns < 1.0) continue;
    measured[static_cast<std::size_t>(axis)] += main;
    truth[static_cast<std::size_t>(axis)] += turns * 2.0 * kPi;
    r.turns_used[static_cast<std::size_t>(axis)] += static_cast<int>(turns);
  }
  for (std::size_t i = 0; i < 3; ++i) {
    if (truth[i] > 0.0) r.scale(static_cast<int>(i)) = measured[i] / truth[i];  // eq. 2.41: K = ∫ω_g / ∫ω
  }
  return r;
}

MagNewtonResult calibrateMagSixPosition(std::span<const StaticSegment> segments, std::span<const Face> faces,
                                        double field_norm_uT, std::optional<double> dip_rad) {
  if (faces.size() != 6) throw CalibrationError("magnetometer: six faces needed");
  const bool estimate_dip = !dip_rad.has_value();
  const int unknowns = estimate_dip ? 10 : 9;
  // x = (α11, α12, α13, α22, α23, α33, b1, b2, b3 [, dip])
  const auto alphaOf = [](const Eigen::VectorXd& x) {
    Mat3 a;
    a << x(0), x(1), x(2), 0.0, x(3), x(4), 0.0, 0.0, x(5);
    return a;
  };
  // Eqs. 2.47a and b for each face: vertical component, and horizontal norm (written as
  // the norm, not its square, so both are in µT).
  const auto equations = [&](const Eigen::VectorXd& x) {
    const Mat3 alpha = alphaOf(x);
    const Vec3 b = x.segment<3>(6);
    const double dip = estimate_dip ? x(9) : *dip_rad;
    const double m_down = field_norm_uT * std::sin(dip), m_hor = field_norm_uT * std::cos(dip);
    Eigen::VectorXd f(12);
    for (std::size_t i = 0; i < 6; ++i) {
      const Face& face = faces[i];
      const Vec3 m = alpha * (segments[face.segment].mag_mean - b);
      f(static_cast<Eigen::Index>(2 * i)) = m(face.axis) - face.sign * m_down;
      double h2 = 0.0;
      for (int j = 0; j < 3; ++j) {
        if (j != face.axis) h2 += m(j) * m(j);
      }
      f(static_cast<Eigen::Index>(2 * i + 1)) = std::sqrt(h2) - m_hor;
    }
    return f;
  };
  // Initial guess: offsets halfway between the opposite faces, unit scale, dip from the
  // faces' vertical readings.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(unknowns);
  double vertical_sum = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    double down = 0.0, up = 0.0;
    for (const Face& f : faces) {
      if (f.axis == axis) (f.sign > 0 ? down : up) = segments[f.segment].mag_mean(axis);
    }
    x(6 + axis) = 0.5 * (down + up);
    vertical_sum += 0.5 * (down - up);
  }
  x(0) = x(3) = x(5) = 1.0;
  const double dip0 = std::asin(std::clamp(vertical_sum / 3.0 / field_norm_uT, -0.99, 0.99));
  if (estimate_dip) x(9) = dip0;

  MagNewtonResult r;
  bool converged = false;
  double cost = equations(x).squaredNorm();
  for (r.iterations = 1; r.iterations <= 100 && !converged; ++r.iterations) {
    const Eigen::VectorXd f = equations(x);
    // Eq. 2.48, by central differences.
    Eigen::MatrixXd j(12, unknowns);
    for (int c = 0; c < unknowns; ++c) {
      const double h = 1e-6 * std::max(1.0, std::abs(x(c)));
      Eigen::VectorXd xp = x, xm = x;
      xp(c) += h;
      xm(c) -= h;
      j.col(c) = (equations(xp) - equations(xm)) / (2.0 * h);
    }
    Eigen::VectorXd dx = -j.colPivHouseholderQr().solve(f);
    if (!dx.allFinite()) break;
    // Algorithm 1 takes the full step; far from the answer (a strongly distorted sensor)
    // that can overshoot, so the step is halved until the equations' residual shrinks.
    double new_cost = equations(x + dx).squaredNorm();
    for (int halving = 0; halving < 30 && !(new_cost <= cost); ++halving) {
      dx *= 0.5;
      new_cost = equations(x + dx).squaredNorm();
    }
    if (!(new_cost <= cost)) {
      converged = true;  // no step lowers the residual: at the least-squares point
      break;
    }
    x += dx;
    converged = dx.norm() < 1e-10 * std::max(1.0, x.norm()) || cost - new_cost < 1e-14 * std::max(1.0, cost);
    cost = new_cost;
  }
  const Eigen::VectorXd f = equations(x);
  if (!f.allFinite() || !converged) {
    throw CalibrationError("magnetometer (Newton, Henriksson Algorithm 1): did not converge in 100 iterations");
  }
  r.alpha = alphaOf(x);
  r.bias_uT = x.segment<3>(6);
  r.dip_rad = estimate_dip ? x(9) : *dip_rad;
  r.residual_rms_uT = std::sqrt(f.squaredNorm() / 12.0);
  if (std::abs(r.alpha.determinant()) < 1e-9) throw CalibrationError("magnetometer: Newton ended at a singular α");
  return r;
}

}  // namespace headingd::calib
