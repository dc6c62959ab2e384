#pragma once
// Small helpers shared by the unit tests: seeded random attitudes and vectors, angles
// between attitudes, and attitudes from yaw/pitch/roll built with Eigen alone (so that the
// code under test is checked against an independent construction).
#include <cmath>
#include <cstdint>
#include <numbers>
#include <ostream>
#include <random>

#include "headingd/core/accel_disturbance.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/core/quaternion.hpp"
#include "headingd/core/sample_gate.hpp"

// GoogleTest prints these by name in failure messages (found by ADL).
namespace headingd::core {
inline void PrintTo(SampleVerdict v, std::ostream* os) { *os << sampleVerdictName(v); }
inline void PrintTo(MotionLevel level, std::ostream* os) { *os << motionLevelName(level); }
}  // namespace headingd::core

namespace headingd::test {

using core::kRadPerDeg;
using core::Quat;
using core::Vec3;
using core::Vec4;

constexpr double kPi = std::numbers::pi;

class Random {
 public:
  explicit Random(std::uint32_t seed) : engine_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }
  double normal(double sigma) { return std::normal_distribution<double>(0.0, sigma)(engine_); }
  Vec3 vector(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
  Vec3 gaussian(double sigma) { return {normal(sigma), normal(sigma), normal(sigma)}; }
  Vec3 unitVector() {
    Vec3 v;
    do {
      v = gaussian(1.0);
    } while (v.norm() < 1e-6);
    return v.normalized();
  }
  // Uniform over rotations (normalised Gaussian 4-vector).
  Quat unitQuat() {
    Vec4 v;
    do {
      v = Vec4{normal(1.0), normal(1.0), normal(1.0), normal(1.0)};
    } while (v.norm() < 1e-6);
    v.normalize();
    return Quat(v(0), v(1), v(2), v(3));
  }
  std::mt19937& engine() { return engine_; }

 private:
  std::mt19937 engine_;
};

// q_nb = R_z(yaw) R_y(pitch) R_x(roll), the zyx (aerospace) sequence, built with Eigen.
inline Quat fromYawPitchRoll(double yaw, double pitch, double roll) {
  return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
              Eigen::AngleAxisd(roll, Vec3::UnitX()));
}

// Rotation angle between two attitudes, in [0, π].
inline double angleBetween(const Quat& a, const Quat& b) { return a.normalized().angularDistance(b.normalized()); }

// Angle between two directions, in [0, π].
inline double angleBetween(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// |a - b| for angles, taking the wrap at ±π into account.
inline double angleDifference(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * kPi)); }

}  // namespace headingd::test
