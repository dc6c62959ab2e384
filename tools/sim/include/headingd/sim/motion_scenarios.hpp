#pragma once
// Scenarios of a sensor handled, shaken or turned slowly, for the estimator's generalisation
// studies: sustained linear acceleration with little rotation, vigorous hand-held
// handling, and gentle slow rotation. Unlike the walking person's scenarios, their motion is
// drawn from the seed (attitudes, shake direction, frequency and amplitude), so a seed sweep is
// a sweep over motions. Each begins and ends with the sensor held still, so that an estimator
// settles first and its recovery can be scored after.
#include <cstdint>

#include "headingd/core/quaternion.hpp"
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

// A sensor held in one attitude (with hand drift and tremor: little rotation) and shaken
// along one direction in its own axes.
struct ShakeSpec {
  core::Quat initial_attitude = core::Quat::Identity();  // sensor to NED
  core::Vec3 direction_body = core::Vec3::UnitX();
  double peak_accel_m_s2 = 30.0;
  double frequency_hz = 4.0;
  double still_before_s = 10.0;
  double shake_s = 60.0;
  double still_after_s = 30.0;
  double tremor_deg = 0.1;      // 6-12 Hz, about the sensor itself (see handheldScenario)
  double hand_drift_deg = 2.0;  // 0.1-0.5 Hz
};

Scenario shakeScenario(const ShakeSpec& spec, std::string name, std::string description);

// "shake": any attitude, along one sensor axis (x, y or z, either sign), 2-8 Hz, 2-7 g.
ShakeSpec drawShakeAlongSensorAxis(std::uint64_t seed);
// "shake-any": any attitude and direction, 0.5-10 Hz, 0.5-8 g.
ShakeSpec drawShakeAnyDirection(std::uint64_t seed);

// Physiological tremor of a hand holding an object is a tenth or two of a m/s² at 6-12 Hz:
// 0.03 deg of rotation at 9 Hz is 1.7 rad/s² of angular acceleration, 0.25 m/s² at 15 cm from
// the wrist. (The shaken sensor turns about itself: its 0.1 deg of tremor only moves the gyro.)
//
// "handheld": 10 s still, 60 s of vigorous handling (a new attitude every 0.4-1.2 s, rates up
// to ~600 deg/s, the hand's translations at 0.5-3 Hz and 0.5-2 g, 15 cm lever arm), 30 s still.
Scenario handheldScenario(std::uint64_t seed);
// "slow-rotation": 10 s still, 90 s of gentle rotation (a new attitude every 3-8 s, tilt up to
// 60 deg, rates mostly 2-25 deg/s), 20 s still.
Scenario slowRotationScenario(std::uint64_t seed);

// A uniformly distributed attitude (normalised 4-D Gaussian).
core::Quat uniformAttitude(std::uint64_t seed, std::uint64_t stream_id);

}  // namespace headingd::sim
