#pragma once
// A scenario: what the person does, phase by phase, where the magnetic field is disturbed
// and how good the GPS sky is. Pure data; trajectory_generator.hpp turns it into motion.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/quaternion.hpp"

namespace headingd::sim {

// kRiding: seated in a vehicle (the vehicle's speed, road vibration instead of steps).
enum class Activity { kStanding, kWalking, kRunning, kCrawling, kLyingBack, kLyingSide, kRiding };
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
  double random_offset_uT = 0.0;                  // plus a constant of this size in a seeded direction
  double spatial_sigma_uT = 0.0;                  // field varying with position (steel in walls, floors)
  double transients_per_min = 0.0;                // passing cars, opened steel doors...
  double transient_peak_uT = 0.0;                 // largest peak; each draws U(0.3, 1) of it
  // Each transient's half width (closest distance / speed) draws U(0.4 s, this): a car
  // passing close by is over in a second, a lift moving past the landing takes several.
  double transient_max_half_width_s = 2.0;
};

struct Phase {
  Activity activity = Activity::kStanding;
  double duration_s = 1.0;
  std::vector<Turn> turns;
  bool indoor = false;  // no GPS fix
  FieldDisturbanceSpec field;
  // Standing without postural sway: the true rate is exactly zero (the short still start of a
  // phone recording, the phone held or set down before the walk begins).
  bool held_still = false;
  // The activity's speed times this: a vehicle stopped at a light (0) or on a faster road.
  double speed_scale = 1.0;
};

// Receiver conditions outdoors (indoors there is never a fix).
struct GpsEnvironment {
  double outlier_probability = 0.0;  // per epoch: start of a multipath jump
  double outage_rate_per_min = 0.0;  // short outdoor outages (urban canyon, under a bridge)
  int satellites = 10;               // typical number used
};

// A sensor turned by hand or set down on a table, for calibration recordings: the attitude
// follows keyframes of zyx Euler angles (roll, pitch, yaw of the sensor, degrees) at given
// times. Between two keyframes each angle moves along a smootherstep (zero rate and angular
// acceleration at both keyframes); two equal keyframes hold the sensor still. The angles
// are not wrapped, so a keyframe 360° on from the last one is a full turn. The rotation is
// about a fixed point; the sensor sits `lever_arm_body_m` from it (body axes), so turning
// also accelerates it (zero lever arm: pure rotation, Kok & Schön §8).
struct OrientationKeyframe {
  double t_s = 0.0;
  double roll_deg = 0.0;
  double pitch_deg = 0.0;
  double yaw_deg = 0.0;
};

// A linear shake of the sensor on top of the scripted rotation: its position moves back and
// forth along a fixed direction in sensor axes, x(t) = -(A/ω²) e(t) sin(ω (t - start)), so
// the acceleration along it is A sin(ω (t - start)) while the envelope e(t) is 1. e rises
// and falls along a smootherstep over fade_s at both ends, so the position stays bounded
// and the acceleration continuous.
struct LinearShake {
  core::Vec3 direction_body = core::Vec3::UnitX();  // unit vector, sensor axes
  double peak_accel_m_s2 = 0.0;                     // A
  double frequency_hz = 1.0;                        // ω / 2π
  double start_s = 0.0;
  double end_s = 0.0;
  double fade_s = 1.0;
};

struct ScriptedOrientation {
  std::vector<OrientationKeyframe> keyframes;  // t_s increasing, the first at 0
  std::vector<LinearShake> shakes;             // may overlap; the displacements add
  core::Vec3 lever_arm_body_m = core::Vec3::Zero();
  double height_m = 1.0;  // of the rotation centre above the ground
  // Hand tremor: small rotations (a seeded sum of sinusoids at 6-12 Hz, physiological tremor)
  // plus a slow drift of the hand (0.1-0.5 Hz); 0 on a table.
  double tremor_deg = 0.0;
  double hand_drift_deg = 0.0;
  // The truth's `moving` flag: the scripted rate (without tremor) above this, or a shake
  // under way.
  double moving_rate_deg_s = 2.0;
};

// A phone carried by the walking person (phone_scenarios.hpp): it rides on a limb (forearm,
// arm, thigh) that turns about the body's y axis through a pivot (elbow, shoulder, hip) as the
// gait goes on. The limb frame is the body frame turned by the limb angle about body y
// (positive: the limb's lower end swings forward); the limb angle is
//     w · (mean + amplitude · sin(stride phase + phase_rad)),
// with the walking figures at walking speed, the running ones at running speed (blended in
// between), and w rising from 0 at standing to 1 at walking speed, so a standing person holds
// the phone still in its rest pose (limb angle 0).
struct CarrySpec {
  std::string mode;                                   // "texting", "calling", ... (descriptions, tests)
  core::Quat q_limb_sensor = core::Quat::Identity();  // sensor to limb: how the phone sits in hand or pocket
  core::Vec3 pivot_body_m = core::Vec3::Zero();       // the pivot from the body's reference point, body axes
  core::Vec3 sensor_limb_m = core::Vec3::Zero();      // the phone from the pivot, limb axes
  double walk_mean_deg = 0.0;
  double walk_amplitude_deg = 0.0;
  double run_mean_deg = 0.0;
  double run_amplitude_deg = 0.0;
  double phase_rad = 0.0;  // offset in the stride cycle (e.g. pi between the left and the right limb)
};

struct Scenario {
  std::string name;
  std::string description;
  double initial_heading_deg = 0.0;
  std::vector<Phase> phases;
  GpsEnvironment gps;
  // Set for calibration scenarios: the attitude comes from the keyframes instead of the
  // person's gait (phases then only give the duration, field and GPS conditions).
  std::optional<ScriptedOrientation> scripted;
  // Set for phone scenarios: the sensor is a phone carried by the walking person, not a unit
  // fixed to the torso.
  std::optional<CarrySpec> carry;

  double durationS() const;
};

// A scripted scenario: one standing phase as long as the script (outdoors, undisturbed field,
// clean GPS); the person holds or turns the sensor and does not walk.
Scenario scriptedScenario(std::string name, std::string description, ScriptedOrientation script);

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
// Throws std::invalid_argument for an unknown name. Most scenarios are the same for every
// seed (the seed changes only the noise); the motion-study scenarios
// (motion_scenarios.hpp) draw their motion from it.
Scenario makeScenario(std::string_view name, std::uint64_t seed = 1);

}  // namespace headingd::sim
