#include "headingd/sim/calibration_scenarios.hpp"

#include <cmath>

namespace headingd::sim {

namespace {

// Appends a move to (roll, pitch, yaw) taking move_s, then a hold of hold_s.
void moveAndHold(ScriptedOrientation& s, double move_s, double hold_s, double roll, double pitch, double yaw) {
  const double t = s.keyframes.back().t_s + move_s;
  s.keyframes.push_back({t, roll, pitch, yaw});
  if (hold_s > 0.0) s.keyframes.push_back({t + hold_s, roll, pitch, yaw});
}

}  // namespace

Scenario calibSixPosition() {
  ScriptedOrientation script;
  constexpr double kHold = 10.0, kMove = 4.0, kTurn = 6.0, kRest = 5.0;
  // Faces (roll, pitch, yaw in degrees): z down, z up, x down, x up, y down, y up. Each
  // face at another yaw, as a user would not line the box up with north.
  script.keyframes = {{0.0, 0.0, 0.0, 20.0}, {kHold, 0.0, 0.0, 20.0}};
  moveAndHold(script, kMove, kHold, 180.0, 0.0, 65.0);
  moveAndHold(script, kMove, kHold, 0.0, -90.0, 110.0);
  moveAndHold(script, kMove, kHold, 0.0, 90.0, 160.0);
  moveAndHold(script, kMove, kHold, 90.0, 0.0, 210.0);
  moveAndHold(script, kMove, kHold, -90.0, 0.0, 250.0);
  // Back to level, then two full turns about x, y and z in turn (Henriksson §2.8.2's
  // chair): each rotation ends where it began, so its angle is a whole number of turns.
  moveAndHold(script, kMove, kRest, 0.0, 0.0, 0.0);
  moveAndHold(script, kTurn, kRest, 720.0, 0.0, 0.0);
  moveAndHold(script, kTurn, kRest, 720.0, 720.0, 0.0);
  moveAndHold(script, kTurn, kRest, 720.0, 720.0, 720.0);
  return scriptedScenario(
      "calib-six-position",
      "Calibration on a table (Henriksson 2013 sec. 2.8): six static faces of 10 s (z down, z up, x down, x up, "
      "y down, y up; 4 s moves between), back to level, then two full turns about x, y and z in turn with 5 s "
      "rests. No tremor, rotation about the sensor.",
      std::move(script));
}

Scenario calibRotation() {
  ScriptedOrientation script;
  script.keyframes = {{0.0, 0.0, 0.0, 0.0}, {1.0, 0.0, 0.0, 0.0}};
  moveAndHold(script, 1.0, 0.0, 360.0, 0.0, 0.0);
  moveAndHold(script, 1.0, 0.0, 360.0, 360.0, 0.0);
  moveAndHold(script, 1.0, 0.0, 360.0, 360.0, 360.0);
  return scriptedScenario(
      "calib-rotation",
      "Kok & Schon 2016 sec. 8: 1 s still (100 samples at 100 Hz), then 3 s (300 samples) of rotation, a full "
      "turn about x, y and z in turn, exactly about the accelerometer (no acceleration). Use with --imu-grade "
      "uncalibrated for Table 2's distortions.",
      std::move(script));
}

Scenario calibRotationLong() {
  ScriptedOrientation script;
  script.tremor_deg = 0.3;
  script.hand_drift_deg = 1.5;
  script.lever_arm_body_m = core::Vec3(0.10, 0.0, 0.0);
  script.keyframes = {{0.0, 0.0, 0.0, 30.0}, {5.0, 0.0, 0.0, 30.0}};
  // 25 poses: roll and pitch swing through their ranges at incommensurate rates while yaw
  // keeps turning, so gravity and the field visit every direction in sensor axes.
  for (int j = 1; j <= 25; ++j) {
    const double roll = 170.0 * std::sin(0.9 * j);
    const double pitch = 80.0 * std::sin(0.55 * j + 0.3);
    const double yaw = 30.0 + 70.0 * j;
    moveAndHold(script, 1.5, 0.5, roll, pitch, yaw);
  }
  moveAndHold(script, 1.5, 3.5, 0.0, 0.0, 30.0 + 70.0 * 26);
  return scriptedScenario(
      "calib-rotation-long",
      "Hand-held calibration, 60 s: 5 s still, 25 poses covering the sphere (1.5 s moves, 0.5 s pauses), "
      "back to level and still to the end. Hand tremor (0.3 deg at 6-12 Hz, 1.5 deg slow drift), sensor 10 cm "
      "from the wrist.",
      std::move(script));
}

}  // namespace headingd::sim
