#pragma once
// Short forms for the scenario lists: a phase of an activity, outdoors or in a disturbed field.
#include <utility>
#include <vector>

#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

inline Phase phase(Activity a, double duration_s, std::vector<Turn> turns = {}) {
  Phase p;
  p.activity = a;
  p.duration_s = duration_s;
  p.turns = std::move(turns);
  return p;
}

// Outdoors (a fix) in a disturbed field: passing cars, a street's steel.
inline Phase fieldPhase(Activity a, double duration_s, const FieldDisturbanceSpec& field,
                        std::vector<Turn> turns = {}) {
  Phase p = phase(a, duration_s, std::move(turns));
  p.field = field;
  return p;
}

// Indoors: no fix, and the building's field.
inline Phase indoorPhase(Activity a, double duration_s, const FieldDisturbanceSpec& field,
                         std::vector<Turn> turns = {}) {
  Phase p = fieldPhase(a, duration_s, field, std::move(turns));
  p.indoor = true;
  return p;
}

}  // namespace headingd::sim
