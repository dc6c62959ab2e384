#pragma once
// Magnetic disturbance detection for the gain K of Henriksson eq. 4.2 (§4.2): K = 0 while
// the field is disturbed, so the heading runs on the gyro alone (eq. 4.3).
//
// Two tests, each against a low-pass of the same quantity (so that a building that weakens
// the field for minutes is accepted again once the low-pass has followed it, as §4.2 asks):
//  - field strength: Δm = ||m| - |m_lp|| (eq. 4.5);
//  - dip angle: a disturbance that keeps the strength but turns the field changes the angle
//    between the field and gravity, which a clean Earth field keeps constant.
// The WMM-referenced tests of the roadmap (issue 4) add to these.
#include "headingd/core/low_pass.hpp"

namespace headingd::core {

struct MagDisturbanceParams {
  double time_constant_s;      // low-pass of strength and dip (§4.2: about 3 s)
  double max_norm_deviation_uT;
  double max_dip_deviation_rad;
};

class MagDisturbanceDetector {
 public:
  explicit MagDisturbanceDetector(const MagDisturbanceParams& p)
      : p_(p), norm_lp_(p.time_constant_s), dip_lp_(p.time_constant_s) {}

  // Returns true when the sample is disturbed.
  bool update(double field_norm_uT, double dip_rad, double dt_s);
  double normDeviation() const { return norm_deviation_; }
  double dipDeviation() const { return dip_deviation_; }

 private:
  MagDisturbanceParams p_;
  LowPass<double> norm_lp_;
  LowPass<double> dip_lp_;
  double norm_deviation_ = 0.0;
  double dip_deviation_ = 0.0;
};

}  // namespace headingd::core
