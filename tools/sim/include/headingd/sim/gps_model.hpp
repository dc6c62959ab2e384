#pragma once
// What a consumer GNSS receiver worn by the person reports, one epoch every 1/rate seconds
// at t = j / rate on the IMU's time axis (j = 0, 1, ...).
//
// Errors: a slowly wandering position error (first-order Gauss-Markov) plus a little white
// noise; velocity, the mean over the epoch interval, with its own small correlated error, so the course noise
// grows as the speed falls (σ_course ≈ σ_v / speed). Below a static-hold speed the receiver
// reports speed 0 and keeps its last course (the behaviour of common receivers; empty until
// a first course exists). No fix indoors and during outdoor outages; after the sky clears
// the fix returns after a few seconds of reacquisition. Now and then a multipath outlier
// shifts position (and velocity) for one to three epochs.
#include <optional>
#include <vector>

#include "headingd/sim/local_frame.hpp"
#include "headingd/sim/rng.hpp"
#include "headingd/sim/scenario.hpp"
#include "headingd/sim/trajectory.hpp"

namespace headingd::sim {

struct GpsReceiverParams {
  double horizontal_sigma_m = 1.5;  // per axis, Gauss-Markov (CEP of a few metres)
  double vertical_sigma_m = 3.0;
  double position_time_s = 60.0;
  double position_white_m = 0.3;
  double velocity_sigma_mps = 0.08;  // per horizontal axis: ~3.4° course noise at 1.35 m/s
  double velocity_time_s = 2.0;
  double static_hold_mps = 0.3;
  double reacquire_min_s = 2.0;
  double reacquire_max_s = 8.0;
  double outage_min_s = 3.0;
  double outage_max_s = 10.0;
  double outlier_min_m = 8.0;
  double outlier_max_m = 30.0;
  double outlier_velocity_min_mps = 0.3;
  double outlier_velocity_max_mps = 1.2;
  int outlier_max_epochs = 3;
};

struct GpsEpoch {
  double t_s = 0.0;
  bool fix = false;
  bool outlier = false;
  // Reported (meaningful only with a fix).
  Geodetic position;
  double speed_mps = 0.0;
  std::optional<double> course_deg;  // true, [0, 360)
  int satellites = 0;
  double hdop = 99.99;
  // Truth: position at t; speed and course of the true mean velocity over the epoch
  // interval (t - 1/rate, t], which is what the receiver measures (course 0 when standing).
  Geodetic true_position;
  double true_speed_mps = 0.0;
  double true_course_deg = 0.0;
};

std::vector<GpsEpoch> simulateGps(const Scenario& scenario, const Trajectory& trajectory, const LocalFrame& frame,
                                  double gps_rate_hz, Rng rng, const GpsReceiverParams& params = {});

}  // namespace headingd::sim
