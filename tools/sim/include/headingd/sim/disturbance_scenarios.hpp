#pragma once
// Issue 29's scenarios for the updates from the field's direction (docs/field-updates.md): an
// indoor walk through fields that are wrong but constant, a walk past fields that change in
// time, and a vehicle ride (sustained acceleration in a clean field).
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

Scenario indoorStaticScenario();        // "indoor-static"
Scenario movingDisturbancesScenario();  // "moving-disturbances"
Scenario vehicleRideScenario();         // "vehicle-ride"

}  // namespace headingd::sim
