#pragma once
// Henriksson (2013) §2.8 calibration routines on the static segments of a recording.
//   accelerometer  a_a = K_a a_p + b_a, K_a diagonal (eq. 2.40): six faces, each axis once
//                  up and once down, K = (a⁺ − a⁻)/2g, b = (a⁺ + a⁻)/2.
//   gyroscope      ω_g = K_g ω_p + b_g (eq. 2.41): b_g the mean at rest; K_g from whole
//                  turns about one axis between two rests (Henriksson counted revolutions in
//                  the magnetometer; here the rests before and after must show the same
//                  gravity and field directions, and the integrated angle is rounded to whole
//                  turns).
//   magnetometer   m = α (m̂ − b), α upper triangular (eqs. 2.45-2.46): on each face the
//                  vertical axis must read the vertical field component (eq. 2.47a) and the
//                  two horizontal axes the horizontal norm (eq. 2.47b); solved by Newton's
//                  method (Algorithm 1) -- with six faces there are twelve equations, so the
//                  Gauss-Newton form of the step, which is Newton's for a square system.
#include <array>
#include <optional>
#include <span>
#include <vector>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/calib/static_segments.hpp"
#include "headingd/core/imu_calibration.hpp"

namespace headingd::calib {

// A static segment in which one sensor axis is vertical: which axis (0..2), whether it
// points down (+1, the accelerometer reads −g on it) or up (−1), and the segment's index.
struct Face {
  int axis = 2;
  int sign = 1;  // +1: the axis points down (NED down), −1: up
  std::size_t segment = 0;
};

// The longest static segment of each of the six faces (axis within `max_tilt_deg` of the
// vertical). Throws CalibrationError naming the faces that are missing.
std::vector<Face> findSixFaces(std::span<const StaticSegment> segments, double max_tilt_deg = 15.0);

struct AccelSixPositionResult {
  core::Vec3 scale = core::Vec3::Ones();
  core::Vec3 bias_m_s2 = core::Vec3::Zero();
};
AccelSixPositionResult calibrateAccelSixPosition(std::span<const StaticSegment> segments, std::span<const Face> faces,
                                                 double gravity_m_s2 = 9.81);

struct GyroBiasResult {
  core::Vec3 bias_rad_s = core::Vec3::Zero();
  core::Vec3 noise_sigma_rad_s = core::Vec3::Zero();
  std::size_t samples = 0;
};
// From the longest static segment.
GyroBiasResult gyroBiasAtRest(std::span<const StaticSegment> segments);

struct GyroScaleResult {
  core::Vec3 scale = core::Vec3::Ones();
  std::array<int, 3> turns_used{0, 0, 0};  // whole turns found per axis (0: scale left at 1)
};
// Looks at the motion between consecutive static segments. `bias` is subtracted first.
GyroScaleResult gyroScaleFromTurns(std::span<const core::ImuSample> samples, std::span<const StaticSegment> segments,
                                   const core::Vec3& bias_rad_s, double rate_hz);

struct MagNewtonResult {
  core::Mat3 alpha = core::Mat3::Identity();  // m = α (m̂ − b), upper triangular
  core::Vec3 bias_uT = core::Vec3::Zero();
  double dip_rad = 0.0;  // used (given) or estimated
  double residual_rms_uT = 0.0;
  int iterations = 0;
};
// `field_norm_uT` the field magnitude; `dip_rad` if known (WMM), else estimated with the
// rest (ten unknowns, twelve equations). Throws CalibrationError if Newton does not converge.
MagNewtonResult calibrateMagSixPosition(std::span<const StaticSegment> segments, std::span<const Face> faces,
                                        double field_norm_uT, std::optional<double> dip_rad);

}  // namespace headingd::calib
