#pragma once
// Where a carried phone is at one instant of the gait (CarrySpec in scenario.hpp): its
// attitude in the body and its place from the body's reference point (the torso point the
// walking trajectory moves).
#include "headingd/core/quaternion.hpp"
#include "headingd/sim/gait.hpp"
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

struct CarryPose {
  core::Quat q_b_sensor = core::Quat::Identity();  // sensor (phone) to body
  core::Vec3 offset_body_m = core::Vec3::Zero();   // the phone from the body's reference point, body axes
  double limb_angle_rad = 0.0;
};

// `gait` is the (blended) gait at that instant: its speed sets how far the limb swings;
// `stride_phase_rad` advances 2 pi per stride (two steps).
CarryPose carryPose(const CarrySpec& carry, const GaitParams& gait, double stride_phase_rad);

}  // namespace headingd::sim
