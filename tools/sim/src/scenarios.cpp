// The named scenarios. Durations are fixed by the phase lists; the seed only changes noise,
// gait jitter, disturbance directions and GPS errors.
#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "headingd/sim/calibration_scenarios.hpp"
#include "headingd/sim/disturbance_scenarios.hpp"
#include "headingd/sim/motion_scenarios.hpp"
#include "headingd/sim/phase_builders.hpp"
#include "headingd/sim/phone_scenarios.hpp"
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

namespace {

// Henriksson (2013) §6.3: straight walks of about 50 s outdoors in four directions in
// Stockholm, GPS course against magnetic heading. Undisturbed field, clean sky.
Scenario thesisDeclination() {
  Scenario s;
  s.name = "thesis-declination";
  s.description =
      "Henriksson 2013 sec. 6.3: stand 10 s, then four straight 50 s walks north, east, south and west, each "
      "followed by a standing pause with a 90 deg right turn in place; stand 10 s. Outdoors, undisturbed "
      "field, consumer GPS, no outliers or outages.";
  s.initial_heading_deg = 0.0;
  s.phases.push_back(phase(Activity::kStanding, 10.0));
  for (int leg = 0; leg < 4; ++leg) {
    s.phases.push_back(phase(Activity::kWalking, 50.0));
    if (leg < 3) s.phases.push_back(phase(Activity::kStanding, 8.0, {{2.5, 3.0, 90.0}}));
  }
  s.phases.push_back(phase(Activity::kStanding, 10.0));
  s.gps = {0.0, 0.0, 10};
  return s;
}

Scenario urbanWalk() {
  Scenario s;
  s.name = "urban-walk";
  s.description =
      "10 minutes in town: standing, walking and running outdoors with turns, passing cars; two buildings "
      "entered (no GPS fix, constant offset, position-dependent field, transients such as steel doors); "
      "multipath outliers and short outages outdoors.";
  s.initial_heading_deg = 30.0;
  FieldDisturbanceSpec street;
  street.transients_per_min = 1.0;
  street.transient_peak_uT = 5.0;
  FieldDisturbanceSpec building_a;
  building_a.random_offset_uT = 8.0;
  building_a.spatial_sigma_uT = 6.0;
  building_a.transients_per_min = 2.0;
  building_a.transient_peak_uT = 25.0;
  FieldDisturbanceSpec building_b = building_a;
  building_b.random_offset_uT = 12.0;
  building_b.spatial_sigma_uT = 4.0;
  const auto outdoor = [&street](Activity a, double d, std::vector<Turn> turns = {}) {
    return fieldPhase(a, d, street, std::move(turns));
  };
  s.phases = {
      outdoor(Activity::kStanding, 10.0),
      outdoor(Activity::kWalking, 50.0, {{20.0, 4.0, 90.0}}),
      outdoor(Activity::kRunning, 30.0, {{10.0, 3.0, -45.0}}),
      outdoor(Activity::kWalking, 20.0, {{12.0, 3.0, -45.0}}),
      indoorPhase(Activity::kWalking, 40.0, building_a, {{15.0, 4.0, 90.0}}),
      indoorPhase(Activity::kStanding, 20.0, building_a),
      indoorPhase(Activity::kWalking, 40.0, building_a, {{2.0, 5.0, 180.0}, {25.0, 4.0, -90.0}}),
      outdoor(Activity::kWalking, 60.0, {{30.0, 4.0, 60.0}}),
      outdoor(Activity::kRunning, 40.0, {{20.0, 4.0, -90.0}}),
      outdoor(Activity::kWalking, 30.0),
      outdoor(Activity::kStanding, 15.0, {{5.0, 3.0, -120.0}}),
      indoorPhase(Activity::kWalking, 45.0, building_b, {{20.0, 5.0, 180.0}}),
      indoorPhase(Activity::kStanding, 30.0, building_b),
      indoorPhase(Activity::kWalking, 30.0, building_b, {{10.0, 4.0, 90.0}}),
      outdoor(Activity::kWalking, 60.0, {{30.0, 3.0, 45.0}}),
      outdoor(Activity::kRunning, 30.0),
      outdoor(Activity::kWalking, 25.0, {{5.0, 4.0, -90.0}}),
      outdoor(Activity::kStanding, 25.0),
  };
  s.gps = {0.02, 0.3, 8};
  return s;
}

Scenario staticDisturbed() {
  Scenario s;
  s.name = "static-disturbed";
  s.description =
      "Standing still for 120 s, heading 60 deg, next to steel: a constant offset (-3, 5, 4) uT NED is added to "
      "the Earth field (at the default place and date: the field's apparent declination is 30.1 instead of 7.7 "
      "deg, |m| 55.4 instead of 51.9 uT, dip 75.3 instead of 72.9 deg). GPS has a fix.";
  s.initial_heading_deg = 60.0;
  Phase p = phase(Activity::kStanding, 120.0);
  p.field.offset_ned_uT = core::Vec3(-3.0, 5.0, 4.0);
  s.phases = {p};
  s.gps = {0.0, 0.0, 9};
  return s;
}

// Henriksson (2013) §6.2's test of the heading redefinition, extended with lying poses.
Scenario crawl() {
  Scenario s;
  s.name = "crawl";
  s.description =
      "Walk 20 s east, get down and crawl 30 s, roll onto the right side (15 s), onto the back (15 s), sit up "
      "and stand (6 s), walk 20 s back west, stand. Head direction kept while rolling. Outdoors, undisturbed.";
  s.initial_heading_deg = 90.0;
  s.phases = {
      phase(Activity::kStanding, 5.0),
      phase(Activity::kWalking, 20.0),
      phase(Activity::kCrawling, 30.0),
      // The head (body -z) keeps pointing the same way: on the side it is 90° left of
      // the body x heading, on the back it is opposite to it.
      phase(Activity::kLyingSide, 15.0, {{0.0, 3.0, -90.0}}),
      phase(Activity::kLyingBack, 15.0, {{0.0, 3.0, -90.0}}),
      phase(Activity::kStanding, 6.0),
      phase(Activity::kWalking, 20.0),
      phase(Activity::kStanding, 5.0),
  };
  s.gps = {0.0, 0.0, 10};
  return s;
}

Scenario run() {
  Scenario s;
  s.name = "run";
  s.description = "Stand 10 s, walk 20 s, run 120 s with four turns, walk 20 s, stand 10 s. Outdoors, undisturbed.";
  s.initial_heading_deg = 200.0;
  s.phases = {
      phase(Activity::kStanding, 10.0),
      phase(Activity::kWalking, 20.0),
      phase(Activity::kRunning, 60.0, {{30.0, 3.0, 90.0}}),
      phase(Activity::kRunning, 60.0, {{20.0, 4.0, -135.0}, {45.0, 3.0, 45.0}}),
      phase(Activity::kWalking, 20.0),
      phase(Activity::kStanding, 10.0),
  };
  s.gps = {0.005, 0.0, 10};
  return s;
}

}  // namespace

const char* activityName(Activity a) {
  switch (a) {
    case Activity::kStanding: return "standing";
    case Activity::kWalking: return "walking";
    case Activity::kRunning: return "running";
    case Activity::kCrawling: return "crawling";
    case Activity::kLyingBack: return "lying_back";
    case Activity::kLyingSide: return "lying_side";
    case Activity::kRiding: return "riding";
  }
  return "unknown";
}

Scenario scriptedScenario(std::string name, std::string description, ScriptedOrientation script) {
  Scenario s;
  s.name = std::move(name);
  s.description = std::move(description);
  s.phases = {phase(Activity::kStanding, script.keyframes.back().t_s)};
  s.initial_heading_deg = script.keyframes.front().yaw_deg;
  s.gps = {0.0, 0.0, 10};
  s.scripted = std::move(script);
  return s;
}

double Scenario::durationS() const {
  return std::accumulate(phases.begin(), phases.end(), 0.0,
                         [](double sum, const Phase& p) { return sum + p.duration_s; });
}

PhaseTime phaseAt(const Scenario& s, double t_s) {
  double start = 0.0;
  for (std::size_t i = 0; i < s.phases.size(); ++i) {
    const double end = start + s.phases[i].duration_s;
    if (t_s < end || i + 1 == s.phases.size()) {
      return {i, std::clamp(t_s - start, 0.0, s.phases[i].duration_s), start};
    }
    start = end;
  }
  return {};
}

std::vector<std::string> scenarioNames() {
  std::vector<std::string> names = {"thesis-declination",
                                    "urban-walk",
                                    "static-disturbed",
                                    "crawl",
                                    "run",
                                    "calib-six-position",
                                    "calib-rotation",
                                    "calib-rotation-long",
                                    "shake",
                                    "shake-any",
                                    "handheld",
                                    "slow-rotation",
                                    "indoor-static",
                                    "moving-disturbances",
                                    "vehicle-ride"};
  for (std::string& name : phoneScenarioNames()) names.push_back(std::move(name));
  return names;
}

Scenario makeScenario(std::string_view name, std::uint64_t seed) {
  if (name == "thesis-declination") return thesisDeclination();
  if (name == "urban-walk") return urbanWalk();
  if (name == "static-disturbed") return staticDisturbed();
  if (name == "crawl") return crawl();
  if (name == "run") return run();
  if (name == "indoor-static") return indoorStaticScenario();
  if (name == "moving-disturbances") return movingDisturbancesScenario();
  if (name == "vehicle-ride") return vehicleRideScenario();
  if (name == "calib-six-position") return calibSixPosition();
  if (name == "calib-rotation") return calibRotation();
  if (name == "calib-rotation-long") return calibRotationLong();
  if (name == "shake") {
    return shakeScenario(drawShakeAlongSensorAxis(seed), "shake",
                         "Shaken along one sensor axis (seeded: any attitude, axis, 2-8 Hz, 2-7 g) for 60 s with "
                         "little rotation (2 deg hand drift, 0.1 deg tremor); 10 s still before, 30 s after.");
  }
  if (name == "shake-any") {
    return shakeScenario(drawShakeAnyDirection(seed), "shake-any",
                         "Shaken along any direction (seeded: any attitude and direction, 0.5-10 Hz, 0.5-8 g) "
                         "for 60 s with little rotation; 10 s still before, 30 s after.");
  }
  if (name == "handheld") return handheldScenario(seed);
  if (name == "slow-rotation") return slowRotationScenario(seed);
  if (isPhoneScenario(std::string(name))) return phoneScenario(std::string(name), seed);
  throw std::invalid_argument("unknown scenario '" + std::string(name) + "'");
}

}  // namespace headingd::sim
