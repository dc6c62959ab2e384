#pragma once
// headingd-replay --smooth: every sample read into memory, the two-filter smoother run over
// them (core/two_filter_smoother.hpp), one row written per sample with the smoothed attitude
// and its heading sigma.
#include <functional>

#include "headingd/core/estimator.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/replay/replay_csv_writer.hpp"
#include "headingd/replay/replay_loop.hpp"

namespace headingd::replay {

struct SmoothedReplay {
  ReplayTotals totals;  // estimator_time: both filters and the fusion, per row as the replay's
  core::EstimatorCounters forward_counters;
};

// start: the pipeline before any sample: its estimator is where both filters begin (its
// parameters; the --place reference field), and its declination (--place) turns each smoothed
// heading into a true one.
SmoothedReplay smoothSamples(const std::function<bool(core::ImuSample*)>& next_sample,
                             const core::HeadingPipeline& start, ReplayCsvWriter& out);

}  // namespace headingd::replay
