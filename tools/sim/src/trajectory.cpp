#include "headingd/sim/trajectory.hpp"

#include <cmath>
#include <stdexcept>

namespace headingd::sim {

using core::Quat;
using core::Vec3;

void requirePositiveRateAndPhases(const Scenario& scenario, double rate_hz) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) throw std::invalid_argument("IMU rate must be positive");
  if (scenario.phases.empty()) throw std::invalid_argument("scenario has no phases");
}

Trajectory kinematicTrajectory(const Scenario& scenario, double rate_hz, const std::vector<Quat>& attitude,
                               const std::vector<Vec3>& position) {
  const double dt = 1.0 / rate_hz;
  const std::size_t rows = attitude.size() - 2;
  Trajectory out;
  out.rate_hz = rate_hz;
  out.q_nb_before_start = attitude[0];
  out.states.resize(rows);
  for (std::size_t k = 0; k < rows; ++k) {
    const std::size_t i = k + 1;
    TruthState& s = out.states[k];
    s.t_s = static_cast<double>(k) * dt;
    s.q_nb = attitude[i];
    s.position_ned_m = position[i];
    s.velocity_ned_mps = (position[i + 1] - position[i - 1]) / (2.0 * dt);
    s.accel_ned_mps2 = (position[i + 1] - 2.0 * position[i] + position[i - 1]) / (dt * dt);
    const PhaseTime pt = phaseAt(scenario, s.t_s);
    s.phase = pt.index;
    s.activity = scenario.phases[pt.index].activity;
    s.indoor = scenario.phases[pt.index].indoor;
  }
  return out;
}

}  // namespace headingd::sim
