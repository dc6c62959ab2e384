#pragma once
// The replay loop: next sample -> estimator -> GPS epochs now due -> one output row, until
// the sample source runs dry (in batches of kBatchRows rows). The source is any callable `bool(core::ImuSample*)`, so
// an IMU CSV and another recorded input feed the same pipeline and writer; nothing is held but the GPS epochs not yet
// due, so memory stays flat whatever the input's length.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "headingd/core/gps_observation.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/imu_then_gps_order.hpp"
#include "headingd/replay/replay_csv_writer.hpp"

namespace headingd::replay {

using GpsOrder = core::ImuThenGpsOrder<core::GpsObservation>;

struct ReplayTotals {
  std::size_t rows = 0;
  // Time in the estimator alone (process() and the GPS epochs it releases); reading and
  // writing are not in it. Two clock reads per row would cost a few percent of the whole
  // replay, so process() is timed on every kTimedEvery-th row and scaled up (the rows of a
  // recording are alike, the sample is spread over all of it); GPS epochs are rare and are
  // always timed.
  std::chrono::nanoseconds estimator_time{0};
};

inline constexpr std::size_t kTimedEvery = 16;
inline constexpr std::size_t kBatchRows = 256;

template <class NextSample>
ReplayTotals replaySamples(NextSample&& next_sample, core::HeadingPipeline& pipeline, GpsOrder& gps,
                           ReplayCsvWriter& out) {
  using Clock = std::chrono::steady_clock;
  Clock::duration gps_time{0}, sampled_time{0};
  std::size_t sampled_rows = 0;
  const auto processGps = [&pipeline, &gps_time](const core::GpsObservation& epoch) {
    const Clock::time_point start = Clock::now();
    pipeline.processGps(epoch);
    gps_time += Clock::now() - start;
  };
  ReplayTotals totals;
  // Rows go through in batches: read a batch, estimate it, write it. Each phase's code and
  // data then stay in the caches for the whole batch (measured: the estimator costs less per
  // sample than when parsing and formatting run between its samples); memory stays a fixed
  // batch whatever the input's length.
  std::vector<core::ImuSample> samples(kBatchRows);
  std::vector<core::HeadingOutput> estimates(kBatchRows);
  for (;;) {
    std::size_t n = 0;
    while (n < kBatchRows && next_sample(&samples[n])) ++n;
    if (n == 0) break;
    for (std::size_t i = 0; i < n; ++i) {
      const core::ImuSample& sample = samples[i];
      if ((totals.rows + i) % kTimedEvery == 0) {
        const Clock::time_point start = Clock::now();
        pipeline.process(sample);
        sampled_time += Clock::now() - start;
        ++sampled_rows;
      } else {
        pipeline.process(sample);
      }
      gps.afterImu(sample.t_ns, processGps);  // each epoch after the first sample at or after its time
      estimates[i] = pipeline.output();       // a rejected sample repeats the last estimate
    }
    for (std::size_t i = 0; i < n; ++i) out.write(samples[i].t_ns, estimates[i]);
    totals.rows += n;
  }
  const double per_row_ns =
      sampled_rows ? static_cast<double>(std::chrono::nanoseconds(sampled_time).count()) / sampled_rows : 0.0;
  totals.estimator_time = std::chrono::nanoseconds(static_cast<std::int64_t>(per_row_ns * totals.rows)) +
                          std::chrono::duration_cast<std::chrono::nanoseconds>(gps_time);
  return totals;
}

}  // namespace headingd::replay
