#pragma once
// The true motion of a walking person: position from integrating the speed along the path
// plus the gait excursions, origin on the ground under the starting point; attitudes from zyx
// Euler angles (yaw = path heading + trunk rotation, pitch and roll = posture + gait
// oscillation + sway).
#include "headingd/sim/rng.hpp"
#include "headingd/sim/scenario.hpp"
#include "headingd/sim/trajectory.hpp"

namespace headingd::sim {

// `rng` gives the small person-to-person and step-to-step variations (speed and cadence
// modulation, heading wander when walking "straight"). Throws std::invalid_argument for a
// non-positive rate or an empty scenario. The scenario's script, if any, is not looked at.
Trajectory generateWalkingTrajectory(const Scenario& scenario, double rate_hz, Rng rng);

}  // namespace headingd::sim
