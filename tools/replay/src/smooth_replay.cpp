#include "headingd/replay/smooth_replay.hpp"

#include <chrono>

#include "headingd/core/two_filter_smoother.hpp"

namespace headingd::replay {

SmoothedReplay smoothSamples(const std::function<bool(core::ImuSample*)>& next_sample,
                             const core::HeadingPipeline& start, ReplayCsvWriter& out) {
  std::vector<core::ImuSample> samples;
  core::ImuSample sample;
  while (next_sample(&sample)) samples.push_back(sample);

  SmoothedReplay result;
  const auto began = std::chrono::steady_clock::now();
  const std::vector<core::AttitudeEstimate> smoothed =
      core::smoothAttitudes(samples, start.estimator(), &result.forward_counters);
  result.totals.estimator_time = std::chrono::steady_clock::now() - began;
  result.totals.rows = samples.size();

  // As the causal replay writes them: the x-axis yaw, the magnetic heading and its sigma, and
  // with --place the true heading from the place's declination; NaN before any estimate. (The
  // smoother keeps no per-sample disturbance flag: mag_disturbed is 0.)
  core::HeadingOutput row = start.output();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const core::AttitudeEstimate& e = smoothed[i];
    row.attitude.valid = e.valid;
    row.attitude.q_nb = e.q_nb;
    row.attitude.yaw_rad = core::yawZyx(e.q_nb);
    row.setMagneticHeading(row.attitude.yaw_rad, std::sqrt(e.covariance_ned(2, 2)));
    out.write(samples[i].t_ns, row);
  }
  return result;
}

}  // namespace headingd::replay
