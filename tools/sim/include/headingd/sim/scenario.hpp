#pragma once
// A scenario: what the person does, phase by phase, where the magnetic field is disturbed
// and how good the GPS sky is. Pure data; trajectory.hpp turns it into motion.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/quaternion.hpp"

namespace headingd::sim {

enum class Activity { kStanding, kWalking, kRunning, kCrawling, kLyingBack, kLyingSide };
const char* activityName(Activity a);  // "standing", "walking", ... (the truth.csv column)

// A smooth heading change inside a phase (clockwise seen from above is positive, as yaw).
struct Turn {
  double start_s = 0.0;  // from the start of the phase
  double duration_s = 3.0;
  double angle_deg = 0.0;
};

// Magnetic disturbances while a phase lasts, all in NED (they belong to the place, not to
// the person). Between phases they blend over a couple of seconds, as when walking in
// through a door.
struct FieldDisturbanceSpec {
  core::Vec3 offset_ned_uT = core::Vec3::Zero();  // fixed part, as given
  double random_offset_uT = 0.0;     // plus a constant of this size in a seeded direction
  double spatial_sigma_uT = 0.0;     // field varying with position (steel in walls, floors)
  double transients_per_min = 0.0;   // passing cars, opened steel doors...
  double transient_peak_uT = 0.0;    // largest peak; each draws U(0.3, 1) of it
};

struct Phase {
  Activity activity = Activity::kStanding;
  double duration_s = 1.0;
  std::vector<Turn> turns;
  bool indoor = false;  // no GPS fix
  FieldDisturbanceSpec field;
};

// Receiver conditions outdoors (indoors there is never a fix).
struct GpsEnvironment {
  double outlier_probability = 0.0;   // per epoch: start of a multipath jump
  double outage_rate_per_min = 0.0;   // short outdoor outages (urban canyon, under a bridge)
  int satellites = 10;                // typical number used
};

struct Scenario {
  std::string name;
  std::string description;
  double initial_heading_deg = 0.0;
  std::vector<Phase> phases;
  GpsEnvironment gps;

  double durationS() const;
};

// Where t falls: the phase index and the time since that phase began. Before 0 it is the
// start of the first phase, after the end the end of the last one.
struct PhaseTime {
  std::size_t index = 0;
  double since_start_s = 0.0;
  double phase_start_s = 0.0;
};
PhaseTime phaseAt(const Scenario& s, double t_s);

// The names makeScenario knows, in the order --help lists them.
std::vector<std::string> scenarioNames();
// Throws std::invalid_argument for an unknown name.
Scenario makeScenario(std::string_view name);

}  // namespace headingd::sim
