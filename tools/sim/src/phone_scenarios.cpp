#include "headingd/sim/phone_scenarios.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "headingd/core/angles.hpp"
#include "headingd/sim/gait.hpp"

namespace headingd::sim {

namespace {

using core::Mat3;
using core::Quat;
using core::Vec3;

constexpr double kPi = std::numbers::pi;
using core::kRadPerDeg;

// Stream ids for the phone scenarios' draws (independent of the other scenarios' and of
// simulation.cpp's sensor streams).
enum PhoneStream : std::uint64_t {
  kPhoneTexting = 111,
  kPhoneCalling,
  kPhoneSwinging,
  kPhonePocket,
  kPhoneRunning,
  kPhoneRunningCircles
};

// Body geometry. A person of 1.75 m with the body's reference point (the torso point the
// walking trajectory moves, 1.3 m up) on the chest; segment lengths and joint heights as
// fractions of the height H from Winter, "Biomechanics and Motor Control of Human Movement"
// (anthropometric table): shoulder 0.818 H (1.43 m, 0.13 m above the chest point, 0.2 m to
// the side), elbow 0.630 H (1.10 m), hip 0.530 H (0.93 m, 0.37 m below), ear ~0.93 H
// (1.63 m), shoulder to the middle of the grip (upper arm 0.186 H + forearm 0.146 H + half
// the palm) ~0.62 m, thigh 0.245 H (0.43 m).
constexpr double kShoulderUp_m = 0.13;
constexpr double kShoulderSide_m = 0.20;
constexpr double kElbowDown_m = 0.20;
constexpr double kHipDown_m = 0.37;
constexpr double kHipSide_m = 0.09;
constexpr double kEarUp_m = 0.32;
constexpr double kArmToGrip_m = 0.62;

double side(Rng& rng) { return rng.uniform01() < 0.5 ? -1.0 : 1.0; }  // +1 right, -1 left

// Sensor axes given in limb axes: the phone's x (its top), its z (out of its back).
Quat fromAxes(const Vec3& x_limb, const Vec3& z_limb) {
  Mat3 r;
  r.col(0) = x_limb.normalized();
  r.col(2) = z_limb.normalized();
  r.col(1) = r.col(2).cross(r.col(0));
  return Quat(r).normalized();
}

Quat about(const Vec3& axis, double angle_rad) { return Quat(Eigen::AngleAxisd(angle_rad, axis.normalized())); }

}  // namespace

// The phone's axes as the sensor axes with an identity carry: x its top, y its right edge
// seen from the screen, z out of its back (so lying screen up, top forward, it is the body
// frame: x forward, y right, z down).

CarrySpec drawTextingCarry(Rng& rng) {
  CarrySpec c;
  c.mode = "texting";
  const double hand = side(rng);
  // The forearm from the elbow to the hand in front of the belly, the screen up and its top
  // raised 20-45 deg (issue 28), turned up to 10 deg off straight ahead (ours).
  const double tilt_deg = rng.uniform(20.0, 45.0);
  const double yaw_deg = rng.uniform(-10.0, 10.0);
  c.q_limb_sensor = about(Vec3::UnitZ(), yaw_deg * kRadPerDeg) * about(Vec3::UnitY(), tilt_deg * kRadPerDeg);
  c.pivot_body_m = Vec3(0.0, hand * 0.18, kElbowDown_m);
  c.sensor_limb_m = Vec3(0.28, -hand * 0.15, 0.05);
  // The hand bobs a little about the elbow with each stride (ours: 2 deg walking, 4 running).
  c.walk_amplitude_deg = 2.0;
  c.run_amplitude_deg = 4.0;
  return c;
}

CarrySpec drawCallingCarry(Rng& rng) {
  CarrySpec c;
  c.mode = "calling";
  const double ear = side(rng);
  // At the ear: the top points up and back (60-80 deg above level, ours: the phone spans ear
  // to mouth), the back of the phone away from the head.
  const double elevation = rng.uniform(60.0, 80.0) * kRadPerDeg;
  c.q_limb_sensor = fromAxes(Vec3(-std::cos(elevation), 0.0, -std::sin(elevation)), Vec3(0.0, ear, 0.0));
  c.sensor_limb_m = Vec3(0.02, ear * 0.08, -kEarUp_m);
  // The head nods little with the stride (ours: 1.5 deg walking, 3 running).
  c.walk_amplitude_deg = 1.5;
  c.run_amplitude_deg = 3.0;
  return c;
}

CarrySpec drawSwingingCarry(Rng& rng) {
  CarrySpec c;
  c.mode = "swinging";
  const double hand = side(rng);
  // Gripped in the hand of the hanging arm, top forward, the screen toward the thigh, rolled
  // in the hand by up to 20 deg (ours).
  c.q_limb_sensor =
      fromAxes(Vec3::UnitX(), Vec3(0.0, hand, 0.0)) * about(Vec3::UnitX(), rng.uniform(-20.0, 20.0) * kRadPerDeg);
  c.pivot_body_m = Vec3(0.0, hand * kShoulderSide_m, -kShoulderUp_m);
  c.sensor_limb_m = Vec3(0.0, 0.0, kArmToGrip_m);
  // The arm a pendulum with the gait, +-30-60 deg (issue 28; more than the +-15-30 deg of an
  // empty hand: a phone swung on purpose). Each arm swings against the leg of its side.
  c.walk_amplitude_deg = rng.uniform(30.0, 60.0);
  c.run_amplitude_deg = c.walk_amplitude_deg;
  c.phase_rad = hand > 0.0 ? 0.0 : kPi;
  return c;
}

CarrySpec drawPocketCarry(Rng& rng) {
  CarrySpec c;
  const double leg = side(rng);
  const bool front = rng.uniform01() < 0.5;
  const bool upright = rng.uniform01() < 0.5;
  c.mode = std::string("pocket-") + (front ? "front" : "back") + (upright ? "-upright" : "-upside-down");
  // Flat on the thigh along it: the top toward the hip (upright) or the knee, the back of the
  // phone outward (forward in a front pocket, backward in a back one), turned about the thigh
  // by up to 30 deg (a front pocket sits toward the side; ours).
  const Vec3 top = upright ? Vec3(0.0, 0.0, -1.0) : Vec3(0.0, 0.0, 1.0);
  const Vec3 back = front ? Vec3::UnitX() : Vec3(-1.0, 0.0, 0.0);
  c.q_limb_sensor = about(Vec3::UnitZ(), rng.uniform(-30.0, 30.0) * kRadPerDeg) * fromAxes(top, back);
  c.pivot_body_m = Vec3(0.0, leg * kHipSide_m, kHipDown_m);
  c.sensor_limb_m = front ? Vec3(0.07, leg * 0.02, 0.15) : Vec3(-0.09, 0.0, 0.08);
  // The thigh's angle in the sagittal plane (hip flexion): walking from ~30 deg forward at
  // heel strike to ~10 deg back (Perry & Burnfield, "Gait Analysis"): mean 10, +-20 deg;
  // running ~45 forward to ~15 back (Novacheck 1998, "The biomechanics of running"): mean 15,
  // +-30 deg. Each leg against the arm of its side.
  c.walk_mean_deg = 10.0;
  c.walk_amplitude_deg = 20.0;
  c.run_mean_deg = 15.0;
  c.run_amplitude_deg = 30.0;
  c.phase_rad = leg > 0.0 ? kPi : 0.0;
  return c;
}

CarrySpec drawRunningHandCarry(Rng& rng) {
  CarrySpec c;
  c.mode = "running-hand";
  const double hand = side(rng);
  // Elbow bent ~90 deg: the fist 0.3 m below and 0.25 m in front of the shoulder, the phone
  // in it top forward, the screen inward, rolled by up to 30 deg (ours). The arm swings with
  // the stride about the shoulder: +-10-20 deg walking, +-30-45 deg running (Novacheck 1998:
  // shoulder flexion-extension of ~70-90 deg range when running).
  c.q_limb_sensor =
      fromAxes(Vec3::UnitX(), Vec3(0.0, hand, 0.0)) * about(Vec3::UnitX(), rng.uniform(-30.0, 30.0) * kRadPerDeg);
  c.pivot_body_m = Vec3(0.0, hand * kShoulderSide_m, -kShoulderUp_m);
  c.sensor_limb_m = Vec3(0.25, -hand * 0.05, 0.30);
  c.walk_amplitude_deg = rng.uniform(10.0, 20.0);
  c.run_amplitude_deg = rng.uniform(30.0, 45.0);
  c.phase_rad = hand > 0.0 ? 0.0 : kPi;
  return c;
}

namespace {

// Loops through a room: straight legs of `leg_m` at `speed_mps`, each ending in a turn of
// 80-100 deg the same way round (now and then a 180 deg turn back), 1.5-2.5 s per 90 deg,
// the person walking on through it. Turn times from the start of the phase.
std::vector<Turn> roomLoops(Rng& rng, double duration_s, double speed_mps, double leg_lo_m, double leg_hi_m) {
  std::vector<Turn> turns;
  const double way = side(rng);
  double t = 1.5;  // the walk starts from standing
  for (;;) {
    t += rng.uniform(leg_lo_m, leg_hi_m) / speed_mps;
    const double angle_deg = rng.uniform01() < 0.15 ? 180.0 * way : way * rng.uniform(80.0, 100.0);
    const double turn_s = rng.uniform(1.5, 2.5) * std::abs(angle_deg) / 90.0;
    if (t + turn_s > duration_s - 1.0) return turns;
    turns.push_back({t, turn_s, angle_deg});
    t += turn_s;
  }
}

// Running round and round in a small hall, as the shared phone recordings' runners do (80-87 %
// of the time turning at about 1.1 rad/s, ~20 turns in two minutes: circles of ~3 m radius at
// 3 m/s): one full circle of radius 2-5 m after another, each a single turn of 360 deg, now
// and then the other way round (a figure of eight). The centripetal acceleration, v²/r ≈ 2-4.5
// m/s², turns with the runner once per circle.
std::vector<Turn> circles(Rng& rng, double duration_s, double speed_mps) {
  std::vector<Turn> turns;
  double way = side(rng);
  double t = 1.0;
  for (;;) {
    const double radius_m = rng.uniform(1.5, 3.5);
    const double circle_s = 2.0 * kPi * radius_m / speed_mps;
    if (t + circle_s > duration_s - 1.0) return turns;
    turns.push_back({t, circle_s, way * 360.0});
    t += circle_s;
    if (rng.uniform01() < 0.25) way = -way;
  }
}

// The room (or hall) the person walks through: indoors (no GPS fix), and a field varying
// with position. 0.5-1 µT per axis (field_model.cpp's spatial modes, 2-12 m wavelengths): at
// the default place (horizontal field ~15 µT) the field's direction varies by ~2-4 deg RMS,
// ~5-10 deg at the extremes, as in an ordinary building with little steel.
Phase indoor(Activity a, double duration_s, const FieldDisturbanceSpec& room, std::vector<Turn> turns = {}) {
  Phase p;
  p.activity = a;
  p.duration_s = duration_s;
  p.turns = std::move(turns);
  p.indoor = true;
  p.field = room;
  return p;
}

enum class Course { kRoomLoops, kHallRuns, kCircleRuns };

Scenario phoneWalk(Rng& rng, std::string name, std::string description, CarrySpec carry, Course course) {
  Scenario s;
  s.name = std::move(name);
  s.description = std::move(description);
  s.initial_heading_deg = rng.uniform(0.0, 360.0);
  FieldDisturbanceSpec room;
  room.spatial_sigma_uT = rng.uniform(0.5, 1.0);
  // The still start of a phone recording: 1-5 s (issue 28), no sway, zero true rate.
  Phase rest = indoor(Activity::kStanding, rng.uniform(1.0, 5.0), room);
  rest.held_still = true;
  s.phases.push_back(rest);
  const double walk_speed = gaitParams(Activity::kWalking).speed_mps;
  if (course == Course::kRoomLoops) {
    // 115 s of loops through a room, legs of 4-9 m.
    s.phases.push_back(indoor(Activity::kWalking, 115.0, room, roomLoops(rng, 115.0, walk_speed, 4.0, 9.0)));
  } else {
    // Walk 15 s, run 80 s along a hall (legs of 15-30 m) or round in circles, walk 15 s.
    const double run_speed = gaitParams(Activity::kRunning).speed_mps;
    s.phases.push_back(indoor(Activity::kWalking, 15.0, room, roomLoops(rng, 15.0, walk_speed, 4.0, 9.0)));
    s.phases.push_back(indoor(
        Activity::kRunning, 80.0, room,
        course == Course::kCircleRuns ? circles(rng, 80.0, run_speed) : roomLoops(rng, 80.0, run_speed, 15.0, 30.0)));
    s.phases.push_back(indoor(Activity::kWalking, 15.0, room, roomLoops(rng, 15.0, walk_speed, 4.0, 9.0)));
  }
  s.gps = {0.0, 0.0, 10};  // indoors: never a fix
  s.carry = std::move(carry);
  return s;
}

// A running person's phone: in the hand or in a trouser pocket, an even draw.
Scenario phoneRun(std::uint64_t seed, PhoneStream stream, std::string name, const char* description, Course course) {
  Rng rng = Rng::stream(seed, stream);
  CarrySpec carry = rng.uniform01() < 0.5 ? drawRunningHandCarry(rng) : drawPocketCarry(rng);
  return phoneWalk(rng, std::move(name), description, std::move(carry), course);
}

const char* kRoom =
    " Starts still for 1-5 s, then walks loops through a room (legs 4-9 m, 80-100 deg turns, now and then "
    "a turn back) whose field varies 0.5-1 uT per axis with position (a few degrees of direction); indoors.";

}  // namespace

std::vector<std::string> phoneScenarioNames() {
  return {"phone-texting", "phone-calling", "phone-swinging", "phone-pocket", "phone-running", "phone-running-circles"};
}

bool isPhoneScenario(const std::string& name) {
  const auto names = phoneScenarioNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

Scenario phoneScenario(const std::string& name, std::uint64_t seed) {
  if (name == "phone-texting") {
    Rng rng = Rng::stream(seed, kPhoneTexting);
    CarrySpec carry = drawTextingCarry(rng);
    return phoneWalk(rng, name,
                     std::string("A phone held in front, screen up, top raised 20-45 deg, bobbing 2 deg with the "
                                 "stride (seeded).") +
                         kRoom,
                     std::move(carry), Course::kRoomLoops);
  }
  if (name == "phone-calling") {
    Rng rng = Rng::stream(seed, kPhoneCalling);
    CarrySpec carry = drawCallingCarry(rng);
    return phoneWalk(rng, name,
                     std::string("A phone at the left or right ear, top up and back 60-80 deg above level "
                                 "(seeded).") +
                         kRoom,
                     std::move(carry), Course::kRoomLoops);
  }
  if (name == "phone-swinging") {
    Rng rng = Rng::stream(seed, kPhoneSwinging);
    CarrySpec carry = drawSwingingCarry(rng);
    return phoneWalk(rng, name,
                     std::string("A phone in the hand of the hanging arm, swung +-30-60 deg with the gait, 0.62 m "
                                 "below the shoulder (seeded).") +
                         kRoom,
                     std::move(carry), Course::kRoomLoops);
  }
  if (name == "phone-pocket") {
    Rng rng = Rng::stream(seed, kPhonePocket);
    CarrySpec carry = drawPocketCarry(rng);
    return phoneWalk(rng, name,
                     std::string("A phone in a front or back trouser pocket, upright or upside down, left or right "
                                 "(seeded), turning with the thigh (10 +- 20 deg).") +
                         kRoom,
                     std::move(carry), Course::kRoomLoops);
  }
  if (name == "phone-running") {
    return phoneRun(seed, kPhoneRunning, name,
                    "A phone in the hand (elbow bent, arm swinging +-30-45 deg) or in a trouser pocket (thigh "
                    "15 +- 30 deg), seeded. Starts still for 1-5 s, walks 15 s, runs 80 s along a hall (legs "
                    "15-30 m, 80-100 deg turns), walks 15 s; the field varies 0.5-1 uT per axis with position; "
                    "indoors.",
                    Course::kHallRuns);
  }
  if (name == "phone-running-circles") {
    return phoneRun(seed, kPhoneRunningCircles, name,
                    "A phone in the hand or in a trouser pocket as in phone-running (seeded). Starts still for "
                    "1-5 s, walks 15 s of loops, runs 80 s round and round (circles of 1.5-3.5 m radius, now and "
                    "then the other way round), walks 15 s; the field varies 0.5-1 uT per axis with position; "
                    "indoors.",
                    Course::kCircleRuns);
  }
  throw std::invalid_argument("unknown phone scenario '" + name + "'");
}

}  // namespace headingd::sim
