#pragma once
// Kok & Schön (2016) §6.2: the rotation R_D between the magnetometer's ellipsoid-fit frame
// and the inertial axes, and the vertical component of the unit field, from the invariance
// of the inner product of the field and the vertical (eq. 27):
//   min over R_D ∈ SO(3), m_z of ½ Σ_t (m_z - v_b,tᵀ R_Dᵀ u_t)²,
// with u_t = D̃0⁻¹(y_m,t - o0) the magnetometer on the fitted unit sphere and v_b,t the
// vertical in body axes from the inertial-only EKF (inclination_ekf.hpp).
#include <cstddef>
#include <span>
#include <vector>

#include "headingd/calib/dip_sign.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::calib {

struct MisalignmentEstimate {
  core::Mat3 rotation = core::Mat3::Identity();  // R_D of eq. 25: D̂0 = D̃0 R_D (eq. 28a)
  double field_down = 0.0;                       // m_z of eq. 27 (NED: positive where the field dips down)
  double dip_rad = 0.0;                          // asin(m_z), eq. 28b
  double rms_residual = 0.0;                     // √(mean of (m_z - v·m_b)²)
  int iterations = 0;                            // Gauss-Newton steps of the best start
};

// Gauss-Newton on SO(3) × R (R_Dᵀ ← exp([φ×]) R_Dᵀ, the deviation parametrisation K&S
// suggest), started from each of the 24 rotations that map axes onto axes: eq. 27 has local
// minima, and the fit's lower-triangular D̃0 can be far from the true D (skew of ±30° in
// Table 2). The best minimum is returned; with `expected` known, the best whose m_z has that
// sign (the best of all if none has): eq. 27 has a minimum for each sign of m_z, a mirror
// pair the data cannot tell apart (dip_sign.hpp). Throws CalibrationError when the spans
// differ in length or hold fewer than 10 pairs.
MisalignmentEstimate estimateMisalignment(std::span<const core::Vec3> mag_on_sphere,
                                          std::span<const core::Vec3> vertical_body,
                                          DipSign expected = DipSign::kUnknown);

// Every distinct local minimum the 24 starts reach (|m_z| <= 1; rotations within 5° of a
// better one count as the same), lowest cost first. Same throws as estimateMisalignment.
std::vector<MisalignmentEstimate> misalignmentMinima(std::span<const core::Vec3> mag_on_sphere,
                                                     std::span<const core::Vec3> vertical_body);

}  // namespace headingd::calib
