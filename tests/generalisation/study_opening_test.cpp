// The study's score splits the fitted error into the opening of a run and the rest
// (scoring.hpp: a filter that finds the heading slowly from a start in motion shows it there).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/study/scoring.hpp"

namespace headingd {
namespace {

using core::kRadPerDeg;

TEST(StudyScore, TheOpeningsHeadingErrorIsScoredApartFromTheRest) {
  // 60 s at 100 Hz, the sensor turning slowly about the vertical and rolling a little; the
  // estimate is 10° off in heading for the first 10 s, exact after.
  study::Recording r;
  r.name = "opening";
  r.rate_hz = 100.0;
  for (int i = 0; i < 6000; ++i) {
    const double t = 0.01 * i;
    core::ImuSample s;
    s.t_ns = static_cast<std::int64_t>(i) * 10'000'000;
    r.samples.push_back(s);
    r.truth_nb.push_back(core::Quat(Eigen::AngleAxisd(0.2 * t, core::Vec3::UnitZ()) *
                                    Eigen::AngleAxisd(0.2 * std::sin(t), core::Vec3::UnitX())));
    r.moving.push_back(true);
  }
  std::vector<core::Quat> estimates;
  for (int i = 0; i < 6000; ++i) {
    const double heading_error = i < 1000 ? 10.0 * kRadPerDeg : 0.0;
    estimates.push_back(core::Quat(Eigen::AngleAxisd(heading_error, core::Vec3::UnitZ())) * r.truth_nb[i]);
  }
  const study::RunScore s = study::score(r, estimates, 25.0);
  // The fit takes out about a sixth of the 10° (its mean); what is left is in the first 10 s.
  EXPECT_GT(s.aligned_opening_rmse.heading_rad, 5.0 * kRadPerDeg);
  EXPECT_LT(s.aligned_after_opening_rmse.heading_rad, 2.5 * kRadPerDeg);
  // The two parts are the whole run's samples: 2500 in the opening, 3500 after.
  const auto squares = [](double rmse, double n) { return rmse * rmse * n; };
  EXPECT_NEAR(
      squares(s.aligned_opening_rmse.heading_rad, 2500) + squares(s.aligned_after_opening_rmse.heading_rad, 3500),
      squares(s.aligned_rmse.heading_rad, 6000), 1e-9 * squares(s.aligned_rmse.heading_rad, 6000));
  // A run shorter than its opening has nothing after it.
  EXPECT_TRUE(std::isnan(study::score(r, estimates, 100.0).aligned_after_opening_rmse.heading_rad));
}

}  // namespace
}  // namespace headingd
