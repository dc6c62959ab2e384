#pragma once
// Scores of an estimator run on a Recording: BROAD's metric, the same with constant earth
// and body alignments fitted (how a held-out dataset with its own reference frames is
// scored), and the tilt figures of a motion episode (the worst inclination error while it
// lasts, and how soon it is gone after it ends).
#include <functional>
#include <vector>

#include "headingd/core/estimator.hpp"
#include "headingd/core/orientation_error.hpp"
#include "headingd/study/recording.hpp"

namespace headingd::study {

// The estimator's attitude after each sample (NaN before it has one). `observe`, if given,
// sees the estimator after every sample (for traces).
using EstimatorObserver = std::function<void(std::size_t index, const core::Estimator&)>;
std::vector<core::Quat> runEstimator(const Recording& r, const core::EstimatorParams& params,
                                     const EstimatorObserver& observe = {});

// Error of each estimate against the truth (NaN where either is unknown).
std::vector<core::OrientationError> perSampleErrors(const Recording& r, const std::vector<core::Quat>& estimates);

// The constant rotations q_E (earth) and q_B (body) that bring the estimates closest to the
// truth over the scored samples, truth ≈ q_E ⊗ estimate ⊗ q_B (alternating quaternion means,
// Markley et al. 2007), and the estimates with them applied.
std::vector<core::Quat> alignedEstimates(const Recording& r, const std::vector<core::Quat>& estimates);

// The opening of a recording that the side-by-side table scores apart (s): the time a
// filter takes to find the heading from a start in motion (the shared phone recordings have
// no rest; a magnetometer observer with a 10-15 s time constant converges in about twice that).
inline constexpr double kOpeningS = 25.0;

struct RunScore {
  core::OrientationError rmse{};          // BROAD's, over the scored samples
  core::OrientationError aligned_rmse{};  // the same after alignedEstimates
  // aligned_rmse over the scored samples of the opening (less than opening_s after the first
  // scored sample) and over those after it: a filter that converges slowly from its start
  // shows it in the first (NaN where a part has no samples).
  core::OrientationError aligned_opening_rmse{};
  core::OrientationError aligned_after_opening_rmse{};
  double max_inclination_rad = 0.0;  // over the scored samples
  std::size_t scored = 0;
  std::size_t failed = 0;  // scored samples without an estimate (counted as 180°)
};
// opening_s: where aligned_rmse is split into its opening and the rest.
RunScore score(const Recording& r, const std::vector<core::Quat>& estimates, double opening_s = kOpeningS);

// Share (0-1) of the scored samples whose heading error lies within k of the stated 1-sigma
// (sigmas_rad: the estimator's heading_sigma_rad after each sample); NaN with none scored.
double headingCoverage(const Recording& r, const std::vector<core::Quat>& estimates,
                       const std::vector<double>& sigmas_rad, double k);

// A motion between rests: from the first to the last scored sample.
struct EpisodeScore {
  double motion_start_s = 0.0;
  double motion_end_s = 0.0;
  double inclination_rmse_rad = 0.0;       // during the motion
  double max_inclination_rad = 0.0;        // during the motion
  double max_inclination_after_rad = 0.0;  // from settle_s after its end to the recording's end
  // Time after the motion's end from which the inclination error stays below `settled_rad`
  // (infinite if it never does).
  double settle_time_s = 0.0;
};
EpisodeScore scoreEpisode(const Recording& r, const std::vector<core::Quat>& estimates, double settle_s,
                          double settled_rad);

}  // namespace headingd::study
