#pragma once
// A configured place in a replay (--place, or a recording's [place]): its date chosen as the
// daemon chooses it (the system's when none is given), what the model says there printed on
// stderr, and the place set on the pipeline.
#include "headingd/core/configured_place.hpp"
#include "headingd/core/heading_pipeline.hpp"

namespace headingd::replay {

void usePlace(core::HeadingPipeline& pipeline, const core::ConfiguredPlace& place, const core::WorldMagneticModel& wmm);

}  // namespace headingd::replay
