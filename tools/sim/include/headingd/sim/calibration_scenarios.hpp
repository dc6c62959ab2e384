#pragma once
// Scenarios of calibration recordings: the sensor turned by hand or set on a table
// (ScriptedOrientation). makeScenario() knows them by name; they are declared here so that
// scenarios.cpp stays the list of the walking person's.
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

// Henriksson (2013) §2.8: six static faces (10 s each, 4 s between), then two full turns
// about each sensor axis with rests between (gyroscope scale, §2.8.2). On a table: no tremor.
Scenario calibSixPosition();
// Kok & Schön (2016) §8: 1 s still (100 samples at 100 Hz), then 3 s (300 samples) of
// rotation about x, y and z in turn, a full turn each, about the accelerometer's origin.
Scenario calibRotation();
// A hand-held variant of calibRotation: 60 s, 5 s still, 25 poses that cover the sphere
// with short pauses, 5 s still; hand tremor and a 10 cm lever arm from the wrist.
Scenario calibRotationLong();

}  // namespace headingd::sim
