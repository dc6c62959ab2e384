#pragma once
// How far the sensor's attitude has moved, net of what it swings back and forth: the turn
// that shows a calibration's residual (a hard iron, a misalignment) from a new side. A hard
// iron h left in the sensor's axes is R h in the earth's, so the heading error it makes
// changes only as the attitude R does, and the heading observer (Henriksson eq. 4.2, 15 s)
// sees the swing of a stride or a swung phone only as its mean. So the attitude is
// low-passed over mean_time_s and the angle its mean has moved is counted in steps of at
// least step_rad: a swing the mean does not follow past a step counts nothing, a turn
// counts its angle.
#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class NetTurn {
 public:
  NetTurn(double mean_time_s, double step_rad) : decay_(mean_time_s), step_rad_(step_rad) {}

  // The attitude now (q_nb) after dt_s; returns the angle (rad) by which the attitude's mean
  // passed a step this sample (0 on most samples).
  double update(const Quat& q_nb, double dt_s);

 private:
  ExpDecay decay_;
  double step_rad_;
  bool started_ = false;
  Quat mean_ = Quat::Identity();          // the attitude low-passed (normalised)
  Quat last_counted_ = Quat::Identity();  // the mean when the last step was counted
};

}  // namespace headingd::core
