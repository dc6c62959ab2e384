#pragma once
// Magnetic heading fused with the gyro heading rate by the observer of Henriksson eq. 4.2:
//   ψ_m(k+1) = K ψ_mm + (1 - K)(ψ_m(k) + T_s ψ̇_g).
// The gyro part (ψ_m + T_s ψ̇_g) is the heading of the EKF attitude after its prediction;
// the measured heading ψ_mm comes from the field rotated into the horizontal frame with that
// attitude's roll and pitch. The result is applied as a rotation about the vertical, so the
// magnetometer changes heading only, never roll or pitch.
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

struct MagHeadingMeasurement {
  bool valid = false;
  // ψ_mm - ψ_pred, wrapped to (-π, π]: how far the field says the heading is off.
  double innovation_rad = 0.0;
  double horizontal_uT = 0.0;
  double dip_rad = 0.0;  // angle of the field below the horizon
};

// The field rotated into the horizontal frame: with R(q) = R_z(ψ) R_tilt, the field in NED
// is R_z(ψ) m_h, so ψ_mm = ψ - atan2(m_n,y, m_n,x), computed without Euler angles and hence
// without a singularity at pitch ±90° (where ψ itself is undefined).
MagHeadingMeasurement measureMagHeading(const Quat& q_nb, const Vec3& mag_uT, double min_horizontal_fraction);

// ψ_mm itself: the heading of the body x-axis (eq. 2.31a) plus the innovation. Not part of
// the measurement because the observer needs only the innovation (and atan2 is costly).
double measuredHeading(const Quat& q_nb, const MagHeadingMeasurement& m);

// Gain of eq. 4.2 for a time constant and the actual sample period.
double magObserverGain(double dt_s, double time_constant_s);

// Eq. 4.2 applied to an attitude: the heading moves by K · innovation about the vertical.
Quat applyHeadingCorrection(const Quat& q_nb, double innovation_rad, double gain);

}  // namespace headingd::core
