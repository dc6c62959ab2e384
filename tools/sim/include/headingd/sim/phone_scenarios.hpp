#pragma once
// A person carrying a phone (issue 28's held-out phone recordings): a short still start of
// 1-5 s, then walking loops through a room whose magnetic field varies by a few degrees from
// place to place, the phone carried one way. Everything is drawn from the seed (how the phone
// is held, the room's field, the loops), so a seed sweep is a sweep over people and rooms.
// Each carry's numbers and where they come from are in phone_scenarios.cpp.
#include <cstdint>
#include <string>
#include <vector>

#include "headingd/sim/rng.hpp"
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

// The carry modes, drawn from rng.
// Texting: held in front, screen up, the top tilted up by 20-45 deg from the forearm.
CarrySpec drawTextingCarry(Rng& rng);
// Calling: at the left or right ear, the top pointing up and back, 60-80 deg above level.
CarrySpec drawCallingCarry(Rng& rng);
// Swinging: in the hand of the hanging arm, a pendulum of +-30-60 deg with the gait.
CarrySpec drawSwingingCarry(Rng& rng);
// Pocket: front or back trouser pocket, upright or upside down, left or right thigh, turning
// with the thigh through the gait cycle.
CarrySpec drawPocketCarry(Rng& rng);
// In the hand of a running person: elbow bent, the forearm forward, swinging with the arm.
CarrySpec drawRunningHandCarry(Rng& rng);

// "phone-texting", "phone-calling", "phone-swinging", "phone-pocket", "phone-running",
// "phone-running-circles".
std::vector<std::string> phoneScenarioNames();
bool isPhoneScenario(const std::string& name);
// Throws std::invalid_argument for a name phoneScenarioNames does not list.
Scenario phoneScenario(const std::string& name, std::uint64_t seed);

}  // namespace headingd::sim
