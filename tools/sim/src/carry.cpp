#include "headingd/sim/carry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"

namespace headingd::sim {

CarryPose carryPose(const CarrySpec& carry, const GaitParams& gait, double stride_phase_rad) {
  using core::kRadPerDeg;
  const double walk_speed = gaitParams(Activity::kWalking).speed_mps;
  const double run_speed = gaitParams(Activity::kRunning).speed_mps;
  // 0 standing .. 1 at walking speed; then 0 .. 1 from walking to running speed.
  const double w = std::clamp(gait.speed_mps / walk_speed, 0.0, 1.0);
  const double r = std::clamp((gait.speed_mps - walk_speed) / (run_speed - walk_speed), 0.0, 1.0);
  const double swing = std::sin(stride_phase_rad + carry.phase_rad);
  const double walk_deg = carry.walk_mean_deg + carry.walk_amplitude_deg * swing;
  const double run_deg = carry.run_mean_deg + carry.run_amplitude_deg * swing;
  CarryPose pose;
  pose.limb_angle_rad = w * (walk_deg + r * (run_deg - walk_deg)) * kRadPerDeg;
  const core::Quat q_b_limb(Eigen::AngleAxisd(pose.limb_angle_rad, core::Vec3::UnitY()));
  pose.q_b_sensor = (q_b_limb * carry.q_limb_sensor).normalized();
  pose.offset_body_m = carry.pivot_body_m + q_b_limb * carry.sensor_limb_m;
  return pose;
}

}  // namespace headingd::sim
