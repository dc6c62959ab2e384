#include "headingd/sim/gait.hpp"

#include <algorithm>

namespace headingd::sim {

GaitParams gaitParams(Activity a) {
  GaitParams p;
  switch (a) {
    case Activity::kStanding:
      p.pitch_deg = -2.0;
      p.sway_deg = 0.3;
      break;
    case Activity::kWalking:
      // ~1.35 m/s at 1.9 steps/s; peak accelerations about 1.7 m/s² forward, 2.8 m/s²
      // vertical and 0.9 m/s² lateral (A·(2πf)²).
      p.speed_mps = 1.35;
      p.step_hz = 1.9;
      p.pitch_deg = -4.0;
      p.forward_m = 0.012;
      p.lateral_m = 0.025;
      p.vertical_m = 0.020;
      p.osc_pitch_deg = 1.5;
      p.osc_roll_deg = 2.0;
      p.osc_yaw_deg = 3.0;
      break;
    case Activity::kRunning:
      // ~3 m/s at 2.8 steps/s; vertical peaks about 1.6 g.
      p.speed_mps = 3.0;
      p.step_hz = 2.8;
      p.pitch_deg = -10.0;
      p.forward_m = 0.020;
      p.lateral_m = 0.020;
      p.vertical_m = 0.050;
      p.osc_pitch_deg = 3.0;
      p.osc_roll_deg = 3.0;
      p.osc_yaw_deg = 5.0;
      p.transition_s = 2.0;
      break;
    case Activity::kCrawling:
      // On hands and knees, face down: the chest (body x) points nearly down, the head
      // (body -z) forward.
      p.speed_mps = 0.4;
      p.step_hz = 1.6;
      p.pitch_deg = -80.0;
      p.height_m = 0.6;
      p.forward_m = 0.020;
      p.lateral_m = 0.020;
      p.vertical_m = 0.010;
      p.osc_pitch_deg = 2.0;
      p.osc_roll_deg = 6.0;
      p.osc_yaw_deg = 6.0;
      p.transition_s = 3.0;
      break;
    case Activity::kLyingBack:
      // Chest up; 85° rather than 90° (a pack under the back) keeps the x-axis heading defined.
      p.pitch_deg = 85.0;
      p.height_m = 0.25;
      p.sway_deg = 0.2;
      p.transition_s = 3.0;
      break;
    case Activity::kLyingSide:
      // On the right side: body y points down.
      p.roll_deg = 90.0;
      p.height_m = 0.35;
      p.sway_deg = 0.2;
      p.transition_s = 3.0;
      break;
    case Activity::kRiding:
      // Seated in a car, leaning back a little: 12 m/s (43 km/h) cruising; speed changes
      // blend over 6 s (peak 3.75 m/s² from standstill, a brisk start). The "steps" are the
      // road's vibration at 11 Hz: 0.2 mm vertical (about 1 m/s²), small pitch and roll.
      p = GaitParams{.speed_mps = 12.0,
                     .step_hz = 11.0,
                     .pitch_deg = 8.0,
                     .height_m = 1.0,
                     .forward_m = 0.0001,
                     .lateral_m = 0.0001,
                     .vertical_m = 0.0002,
                     .osc_pitch_deg = 0.1,
                     .osc_roll_deg = 0.15,
                     .osc_yaw_deg = 0.05,
                     .sway_deg = 0.3,
                     .transition_s = 6.0};
      break;
  }
  return p;
}

GaitParams blend(const GaitParams& a, const GaitParams& b, double w) {
  const auto mix = [w](double x, double y) { return x + w * (y - x); };
  GaitParams r;
  r.speed_mps = mix(a.speed_mps, b.speed_mps);
  r.step_hz = mix(a.step_hz, b.step_hz);
  r.pitch_deg = mix(a.pitch_deg, b.pitch_deg);
  r.roll_deg = mix(a.roll_deg, b.roll_deg);
  r.height_m = mix(a.height_m, b.height_m);
  r.forward_m = mix(a.forward_m, b.forward_m);
  r.lateral_m = mix(a.lateral_m, b.lateral_m);
  r.vertical_m = mix(a.vertical_m, b.vertical_m);
  r.osc_pitch_deg = mix(a.osc_pitch_deg, b.osc_pitch_deg);
  r.osc_roll_deg = mix(a.osc_roll_deg, b.osc_roll_deg);
  r.osc_yaw_deg = mix(a.osc_yaw_deg, b.osc_yaw_deg);
  r.sway_deg = mix(a.sway_deg, b.sway_deg);
  r.transition_s = b.transition_s;
  return r;
}

double smootherstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * s * (s * (6.0 * s - 15.0) + 10.0);
}

}  // namespace headingd::sim
