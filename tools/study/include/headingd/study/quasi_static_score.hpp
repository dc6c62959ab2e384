#pragma once
// How well the estimator's quasi-static field detection (core/quasi_static_field.hpp, MAGYQ
// §5) picked its periods, measured with the reference attitude: a field that is constant in
// the navigation frame, read through the reference, stays where it was at the period's start.
// Per block of kBlockS in a period: |mean of R_ref v over the block - the same over the
// period's first block|, v the sensor vector as the estimator used it (turned forward by the
// lag it gave the sample: a phone's magnetometer is tens of ms late and held between its
// readings, which through the reference would swing with every stride). A block's mean keeps
// √(3/n) σ of its n samples' noise: 0.35 σ for 25 samples.
#include <vector>

#include "headingd/study/recording.hpp"

namespace headingd::study {

struct QuasiStaticScore {
  double share = 0.0;       // of the samples with a reference, in a period
  std::size_t periods = 0;  // that had a reference at their start
  double mean_period_s = 0.0;
  // The vector's distance from its period's start through the reference, over the blocks in
  // periods (field unit): median and 95th percentile. NaN without such blocks.
  double median_drift = 0.0;
  double p95_drift = 0.0;
};

// flags and vectors_sensor: one per sample of r, whether the estimator had the vector
// quasi-static there, and the vector (sensor axes).
QuasiStaticScore scoreQuasiStatic(const Recording& r, const std::vector<bool>& flags,
                                  const std::vector<core::Vec3>& vectors_sensor);

}  // namespace headingd::study
