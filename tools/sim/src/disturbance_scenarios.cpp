#include "headingd/sim/disturbance_scenarios.hpp"

#include "headingd/sim/phase_builders.hpp"

namespace headingd::sim {

// Static disturbances: steel in walls and shelves, a radiator, a magnet on a desk. Constant in
// place, so where the person turns on the spot MAGYQ's QSF update could hold the heading.
Scenario indoorStaticScenario() {
  Scenario s;
  s.name = "indoor-static";
  s.description =
      "An office visit: walk in from outdoors, corridors with steel in the walls (position-dependent field), "
      "stand at a radiator (15 uT offset) turning 90 deg, sit 60 s at a desk with a magnet (20 uT) swivelling "
      "+60/-120/+60 deg, steel shelves (12 uT) with a 180 deg turn, walk out. Wrong but constant fields, no fix "
      "indoors.";
  s.initial_heading_deg = 120.0;
  const FieldDisturbanceSpec corridor{.random_offset_uT = 5.0, .spatial_sigma_uT = 4.0};
  const FieldDisturbanceSpec radiator{.random_offset_uT = 15.0};
  const FieldDisturbanceSpec desk_magnet{.random_offset_uT = 20.0};
  const FieldDisturbanceSpec shelves_aisle{.random_offset_uT = 8.0, .spatial_sigma_uT = 8.0};
  const FieldDisturbanceSpec shelves{.random_offset_uT = 12.0};
  const FieldDisturbanceSpec way_out{.spatial_sigma_uT = 3.0};
  s.phases = {
      phase(Activity::kStanding, 10.0),
      phase(Activity::kWalking, 30.0, {{15.0, 4.0, -45.0}}),
      indoorPhase(Activity::kWalking, 40.0, corridor, {{20.0, 4.0, 90.0}}),
      indoorPhase(Activity::kStanding, 20.0, radiator, {{8.0, 3.0, 90.0}}),
      indoorPhase(Activity::kWalking, 30.0, corridor, {{12.0, 5.0, 180.0}}),
      indoorPhase(Activity::kStanding, 60.0, desk_magnet, {{10.0, 3.0, 60.0}, {25.0, 4.0, -120.0}, {45.0, 3.0, 60.0}}),
      indoorPhase(Activity::kWalking, 30.0, shelves_aisle, {{15.0, 4.0, -90.0}}),
      indoorPhase(Activity::kStanding, 20.0, shelves, {{5.0, 5.0, 180.0}}),
      indoorPhase(Activity::kWalking, 30.0, way_out, {{10.0, 4.0, 90.0}}),
      phase(Activity::kWalking, 30.0, {{10.0, 4.0, 45.0}}),
      phase(Activity::kStanding, 10.0),
  };
  s.gps = {0.0, 0.0, 9};
  return s;
}

// Moving disturbances: cars passing a street and a crossing, a lift moving past its landing,
// the steel cabin of the lift. Fields that change in time, which no quasi-static-field test
// may take for constant.
Scenario movingDisturbancesScenario() {
  Scenario s;
  s.name = "moving-disturbances";
  s.description =
      "Walk along a street with passing cars (6/min, up to 15 uT), wait 20 s at a crossing (12/min, up to 20 "
      "uT, 3 s wide), walk into a building, wait 30 s at a lift moving past (4/min, up to 40 uT, 6 s wide), ride "
      "20 s in its steel cabin (25 uT) turning to the door, walk out on another floor. No fix indoors.";
  s.initial_heading_deg = 250.0;
  const FieldDisturbanceSpec street{.transients_per_min = 6.0, .transient_peak_uT = 15.0};
  const FieldDisturbanceSpec crossing{
      .transients_per_min = 12.0, .transient_peak_uT = 20.0, .transient_max_half_width_s = 3.0};
  const FieldDisturbanceSpec hall{.spatial_sigma_uT = 2.0};
  const FieldDisturbanceSpec landing{
      .spatial_sigma_uT = 2.0, .transients_per_min = 4.0, .transient_peak_uT = 40.0, .transient_max_half_width_s = 6.0};
  const FieldDisturbanceSpec cabin{.random_offset_uT = 25.0};
  const FieldDisturbanceSpec upper_floor{.spatial_sigma_uT = 3.0};
  s.phases = {
      fieldPhase(Activity::kStanding, 10.0, street),
      fieldPhase(Activity::kWalking, 40.0, street, {{20.0, 4.0, 90.0}}),
      fieldPhase(Activity::kStanding, 20.0, crossing),
      fieldPhase(Activity::kWalking, 30.0, street, {{5.0, 4.0, -90.0}}),
      indoorPhase(Activity::kWalking, 20.0, hall, {{10.0, 4.0, 45.0}}),
      indoorPhase(Activity::kStanding, 30.0, landing),
      indoorPhase(Activity::kStanding, 20.0, cabin, {{3.0, 4.0, 180.0}}),
      indoorPhase(Activity::kWalking, 30.0, upper_floor, {{15.0, 4.0, -90.0}}),
      indoorPhase(Activity::kStanding, 10.0, upper_floor),
  };
  s.gps = {0.01, 0.0, 8};
  return s;
}

// A car ride: sustained acceleration (starts, stops, bends at speed) while the field is clean:
// gravity is not what the accelerometer measures for seconds at a time.
Scenario vehicleRideScenario() {
  Scenario s;
  s.name = "vehicle-ride";
  s.description =
      "Stand 10 s, get into a car, ride 4.5 min: starts to 12-18 m/s (up to 3.75 m/s2 for 6 s), bends of 90 deg "
      "at 12 m/s (centripetal up to 4.4 m/s2), a stop at a light, a 180 deg turn at 5 m/s, road vibration at "
      "11 Hz; park, get out, stand. Clean field, GPS all the way.";
  s.initial_heading_deg = 340.0;
  const auto ride = [](double duration_s, double speed_scale, std::vector<Turn> turns = {}) {
    Phase p = phase(Activity::kRiding, duration_s, std::move(turns));
    p.speed_scale = speed_scale;
    return p;
  };
  s.phases = {
      phase(Activity::kStanding, 10.0),
      ride(10.0, 0.0),
      ride(60.0, 1.0, {{25.0, 8.0, 90.0}}),
      ride(40.0, 1.5, {{15.0, 10.0, -45.0}}),
      ride(20.0, 0.0),
      ride(50.0, 1.0, {{20.0, 8.0, -90.0}}),
      ride(30.0, 0.4, {{10.0, 10.0, 180.0}}),
      ride(60.0, 1.2, {{30.0, 8.0, 90.0}}),
      ride(15.0, 0.0),
      phase(Activity::kStanding, 10.0),
  };
  s.gps = {0.005, 0.0, 10};
  return s;
}

}  // namespace headingd::sim
