#pragma once
// Posture and gait of each activity. The figures are typical values for adults from gait
// biomechanics (cadence, speed, centre-of-mass excursions); they are the simulator's, not a
// paper's. Linear displacement amplitudes are in the heading frame (forward, right, down),
// which is the body frame of an upright person up to its small lean.
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

struct GaitParams {
  double speed_mps = 0.0;
  double step_hz = 0.0;    // steps (not strides) per second
  double pitch_deg = 0.0;  // posture, zyx Euler angles of the body; forward lean < 0
  double roll_deg = 0.0;
  double height_m = 1.3;  // of the IMU (worn on the torso) above the ground
  // Per step: forward-backward and vertical excursions at the step frequency, lateral sway
  // at half of it (one sway cycle per stride).
  double forward_m = 0.0;
  double lateral_m = 0.0;
  double vertical_m = 0.0;
  // Attitude oscillations: pitch at the step frequency, roll and yaw (trunk rotation) at half.
  double osc_pitch_deg = 0.0;
  double osc_roll_deg = 0.0;
  double osc_yaw_deg = 0.0;
  // Postural sway (standing) or breathing (lying), about pitch and roll, at kSwayHz.
  double sway_deg = 0.0;
  // Time to blend from the previous activity into this one (speed ramp, getting down).
  double transition_s = 1.5;
};

inline constexpr double kSwayHz = 0.25;

GaitParams gaitParams(Activity a);

// Component-wise blend a + w (b - a); w in [0, 1].
GaitParams blend(const GaitParams& a, const GaitParams& b, double w);

// Hermite quintic 6s⁵ - 15s⁴ + 10s³ on s clamped to [0, 1]: zero first and second
// derivatives at both ends, so blended positions have continuous accelerations.
double smootherstep(double s);

}  // namespace headingd::sim
