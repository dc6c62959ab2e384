#pragma once
// Reading a STATUS message in tests: a source by its kind, a counter by its name.
#include <cstdint>
#include <string>

#include "headingd/source_status_t.hpp"
#include "headingd/status_t.hpp"

namespace headingd::daemon::test {

// The first source of this kind ("gps_serial", "can", ...), nullptr when there is none.
inline const headingd::source_status_t* findSource(const headingd::status_t& s, const std::string& kind) {
  for (const auto& src : s.sources) {
    if (src.kind == kind) return &src;
  }
  return nullptr;
}

// One of STATUS's own counters (estimator, loop, recorder) by name, -1 when absent.
inline std::int64_t statusCounter(const headingd::status_t& s, const std::string& name) {
  for (const auto& c : s.counters) {
    if (c.name == name) return c.value;
  }
  return -1;
}

// A source's counter on STATUS by name, -1 when it has none.
inline std::int64_t counter(const headingd::source_status_t& s, const std::string& name) {
  for (const auto& c : s.counters) {
    if (c.name == name) return c.value;
  }
  return -1;
}

}  // namespace headingd::daemon::test
