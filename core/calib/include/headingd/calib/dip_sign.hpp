#pragma once
// What is known of the magnetic dip before the data are seen: its sign, from the WMM at the
// place and date of the recording or from the hemisphere the user names.
//
// Why it is needed: y_m = D R_bn m_n + o is unchanged by (D, δ, yaw) → (-D, -δ, yaw + π),
// since Rz(π) m_n(-δ) = -m_n(δ). Kok & Schön's eq. 27 only sees inner products with the
// vertical, so it has a minimum for each sign of m_z = sin δ, and on a few seconds of
// rotation the wrong one can fit better (K&S §8 runs: 1 in 30, 126° off in dip). The data
// cannot tell the pair apart; the place can.
#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"

namespace headingd::calib {

enum class DipSign {
  kUnknown,
  kDown,  // δ > 0: the field dips below the horizon (northern magnetic hemisphere; NED z down)
  kUp,    // δ < 0: southern magnetic hemisphere
};

// Within this of the magnetic equator the sign says little (the WMM's error, a few tenths of
// a degree, is far smaller, but the local field's anomalies are not): no sign is imposed.
inline constexpr double kDipSignMinimum_rad = 5.0 * core::kRadPerDeg;

// The sign of an expected dip (WMM, rad); kUnknown near the magnetic equator or for NaN.
inline DipSign dipSignOf(double expected_dip_rad) {
  if (!(std::abs(expected_dip_rad) >= kDipSignMinimum_rad)) return DipSign::kUnknown;
  return expected_dip_rad > 0.0 ? DipSign::kDown : DipSign::kUp;
}

// True when a dip of that sine agrees with `sign` (always for kUnknown).
template <typename T>
bool dipAgrees(const T& sin_dip, DipSign sign) {
  switch (sign) {
    case DipSign::kDown: return sin_dip > T(0.0);
    case DipSign::kUp: return sin_dip < T(0.0);
    case DipSign::kUnknown:
    default: return true;
  }
}

inline const char* dipSignName(DipSign s) {
  switch (s) {
    case DipSign::kDown: return "down (northern magnetic hemisphere)";
    case DipSign::kUp: return "up (southern magnetic hemisphere)";
    case DipSign::kUnknown:
    default: return "unknown";
  }
}

}  // namespace headingd::calib
