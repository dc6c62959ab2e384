#pragma once
// The true motion of a scenario: scripted (a calibration recording, scripted_trajectory.hpp)
// when it has a script, else a walking person (walking_trajectory.hpp).
#include "headingd/sim/rng.hpp"
#include "headingd/sim/scenario.hpp"
#include "headingd/sim/trajectory.hpp"

namespace headingd::sim {

// `rng` draws the generator's variations (gait wander, hand tremor). Throws
// std::invalid_argument for a non-positive rate, an empty scenario or a bad script.
Trajectory generateTrajectory(const Scenario& scenario, double rate_hz, Rng rng);

}  // namespace headingd::sim
