#include "headingd/sim/trajectory_generator.hpp"

#include "headingd/sim/scripted_trajectory.hpp"
#include "headingd/sim/walking_trajectory.hpp"

namespace headingd::sim {

Trajectory generateTrajectory(const Scenario& scenario, double rate_hz, Rng rng) {
  requirePositiveRateAndPhases(scenario, rate_hz);
  if (scenario.scripted) return generateScriptedTrajectory(scenario, rate_hz, rng);
  return generateWalkingTrajectory(scenario, rate_hz, rng);
}

}  // namespace headingd::sim
