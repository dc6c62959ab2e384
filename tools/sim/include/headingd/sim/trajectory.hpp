#pragma once
// The true motion, sampled at the IMU rate: attitude of the body, position, velocity and
// acceleration in a local NED frame, as the generators make it (a walking person:
// walking_trajectory.hpp; a sensor turned by hand: scripted_trajectory.hpp; either by the
// scenario: trajectory_generator.hpp). What they share is here.
//
// Consistency: velocity and acceleration are the central first and second differences of
// the positions, so GPS positions, velocities and the accelerometer all describe the same
// motion; the gyroscope is derived from consecutive attitudes (imu_model.hpp), never from
// Euler rates.
#include <cstddef>
#include <vector>

#include "headingd/core/quaternion.hpp"
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

struct TruthState {
  double t_s = 0.0;
  core::Quat q_nb = core::Quat::Identity();  // body to NED
  // A carried phone's attitude in the body (phone scenarios, carry.hpp); identity for a sensor
  // fixed to the torso. The sensor's attitude is q_nb ⊗ q_b_sensor (then the mount).
  core::Quat q_b_sensor = core::Quat::Identity();
  // Of the sensor: the torso point, or the carried phone.
  core::Vec3 position_ned_m = core::Vec3::Zero();
  core::Vec3 velocity_ned_mps = core::Vec3::Zero();
  core::Vec3 accel_ned_mps2 = core::Vec3::Zero();  // kinematic, gravity not included
  double path_heading_rad = 0.0;                   // direction of travel the person intends (no gait wobble)
  std::size_t phase = 0;
  Activity activity = Activity::kStanding;
  bool indoor = false;
  // Anything but still standing or lying: walking, turning, getting up or down.
  bool moving = false;
};

struct Trajectory {
  double rate_hz = 0.0;
  // Row k is at t = k / rate_hz, k = 0 .. floor(duration · rate_hz).
  std::vector<TruthState> states;
  // The body attitude one sample before t = 0: the first gyro row covers (-1/rate, 0].
  core::Quat q_nb_before_start = core::Quat::Identity();
  core::Quat q_b_sensor_before_start = core::Quat::Identity();
};

// The kinematic part of every row of a trajectory sampled at dt with one padding sample on
// each side (attitude and position have rows + 2 entries): time, attitude, position, and
// velocity and acceleration by central differences, plus the scenario's phase at that time.
// path_heading_rad and moving are the generator's to set.
Trajectory kinematicTrajectory(const Scenario& scenario, double rate_hz, const std::vector<core::Quat>& attitude,
                               const std::vector<core::Vec3>& position);

// Throws std::invalid_argument for a non-positive rate or a scenario without phases.
void requirePositiveRateAndPhases(const Scenario& scenario, double rate_hz);

}  // namespace headingd::sim
