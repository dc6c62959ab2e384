#pragma once
// The ML cost's data and parameters on a short K&S §8 run (seed 7: 100 samples at rest, 300
// rotating), θ moved off the initial estimate so that no gradient component is
// accidentally zero. Shared by the cost and gradient tests.
#include <cmath>
#include <cstddef>

#include "headingd/calib/ml/ml_calibration.hpp"
#include "headingd/calib_montecarlo/ks_simulation.hpp"

namespace headingd::calib::test {

struct MlCostFixture {
  MlData data;
  MlParameters theta{};
};

inline MlCostFixture makeMlCostFixture(std::size_t decimation = 1) {
  const calib_montecarlo::KsRun run =
      calib_montecarlo::simulateKokSchonRun(calib_montecarlo::KsVariant::kShort, 7, {0.3, true});
  MlInitialOptions o;
  o.field_norm_uT = run.truth.field_norm_uT;
  o.ellipsoid_min_coverage = 0.1;
  const MlInitialEstimate init = estimateInitialParameters(run.samples, o);
  MlDataOptions d;
  d.field_norm_uT = o.field_norm_uT;
  d.gravity_m_s2 = init.gravity_m_s2;
  d.decimation = decimation;
  MlCostFixture f;
  f.data = prepareMlData(run.samples, d);
  f.theta = packParameters(initialParameterValues(init, o));
  for (int i = 0; i < kMlParameterCount; ++i) f.theta[i] += 0.01 * std::sin(1.0 + i);
  return f;
}

}  // namespace headingd::calib::test
