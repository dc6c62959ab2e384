#pragma once
// The true motion of a calibration recording: the sensor turned through scripted keyframes
// (scenario.hpp, ScriptedOrientation) about a fixed point, with optional hand tremor. The
// same Trajectory as the walking person's, so the IMU, field and output code are shared.
#include "headingd/sim/rng.hpp"
#include "headingd/sim/scenario.hpp"
#include "headingd/sim/trajectory.hpp"

namespace headingd::sim {

// The scripted attitude alone (no tremor) at t, sensor/body to NED.
core::Quat scriptedAttitude(const ScriptedOrientation& script, double t_s);

// `rng` draws the tremor. Throws std::invalid_argument for keyframes out of time order,
// a non-positive rate or a scenario without a script.
Trajectory generateScriptedTrajectory(const Scenario& scenario, double rate_hz, Rng rng);

}  // namespace headingd::sim
