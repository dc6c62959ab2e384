#include "replay_place.hpp"

#include <chrono>
#include <cstdio>

namespace headingd::replay {

void usePlace(core::HeadingPipeline& pipeline, const core::ConfiguredPlace& place,
              const core::WorldMagneticModel& wmm) {
  const std::int64_t now_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  std::string warning;
  const double year = core::placeDecimalYear(place, core::decimalYearOfUnixNs(now_ns), wmm, &warning);
  if (!warning.empty()) std::fprintf(stderr, "headingd-replay: warning: %s\n", warning.c_str());
  std::fprintf(stderr, "headingd-replay: %s\n", core::describePlace(place.position, year, wmm).c_str());
  pipeline.setPlace(place.position, year);
}

}  // namespace headingd::replay
