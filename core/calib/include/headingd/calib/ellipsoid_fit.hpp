#pragma once
// Ellipsoid fit of magnetometer data, Kok & Schön (2016) §6.1, eqs. 19-24.
//
// The measurements y = D m + o + e with |m| = field norm lie on the ellipsoid
// (y - o)ᵀ A (y - o) = 1 with A = (D Dᵀ)⁻¹ / |m|². The fit is the paper's linear least
// squares in the quadric's coefficients (eq. 21), then, because that alone does not
// guarantee a positive-definite A, a Ceres refinement of the same algebraic cost with A
// written through a Cholesky factor (A = L Lᵀ, L lower triangular with a positive diagonal)
// -- the constrained fit equivalent to the paper's SDP. By default a geometric refinement
// follows (options). D is known only up to a rotation (eq. 25): the fit returns the
// symmetric root of D Dᵀ (no rotation added to the soft iron); the misalignment step
// (§6.2) finds the rotation.
#include <span>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::calib {

struct EllipsoidFit {
  core::Mat3 D;            // y = D m + o, symmetric positive definite (up to a rotation)
  core::Vec3 offset_uT;    // o
  double field_norm_uT;    // |m| the fit was scaled to
  double residual_rms_uT;  // RMS of | |D⁻¹(y - o)| - |m| |
  double coverage;         // fraction of the sphere the calibrated directions visit, 0..1
  // Ratio of the largest to the smallest singular value of the fit's Jacobian (field-norm
  // residuals against D⁻¹ and o, in normalised units): how well the data pin the answer
  // down. About 10 for a hand-held minute, 100 and more for three turns about the axes.
  double condition_number = 0.0;
};

struct EllipsoidFitOptions {
  // Below this coverage (fraction of equal-area cells of the unit sphere hit by the
  // calibrated field directions; one full turn about one axis gives about 0.13, Kok &
  // Schön §8's turns about x, y and z 0.3, a hand-held minute 0.8)
  // the fit throws: too little of the ellipsoid was seen.
  double min_coverage = 0.2;
  int min_samples = 30;
  // After the algebraic fit, minimise the field-norm error | |D⁻¹(y - o)| - |m| | itself
  // (Ceres, D⁻¹ upper triangular). Off: the paper's §6.1 estimate alone.
  bool geometric_refinement = true;
  // Weight of the pull of the algebraic fit towards a sphere, used (×0.1, ×1, ×10, as
  // little as works) only when eq. 23 alone gives an implausible ellipsoid: very flat or
  // centred far from the data (ellipsoid_fit.cpp, plausibleQuadric). 0: never.
  double sphere_weight = 1e-2;
};

// Throws CalibrationError for too few samples, non-finite values, rotations that do not
// cover enough of the sphere (the message gives the coverage measured), or data that
// no ellipsoid fits.
EllipsoidFit fitEllipsoid(std::span<const core::Vec3> mag_uT, double field_norm_uT, const EllipsoidFitOptions& options);
inline EllipsoidFit fitEllipsoid(std::span<const core::Vec3> mag_uT, double field_norm_uT) {
  return fitEllipsoid(mag_uT, field_norm_uT, EllipsoidFitOptions{});
}

// The coverage figure of EllipsoidFit: the fraction of 200 equal-area cells of the unit
// sphere (a Fibonacci lattice, nearest centre) that at least one direction falls into.
double sphereCoverage(std::span<const core::Vec3> directions);

}  // namespace headingd::calib
