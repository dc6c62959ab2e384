#include "headingd/calib/ml/ml_adjoint_gradient.hpp"

// ml_reverse_scalar.hpp first: its NumTraits must be seen before Eigen uses the scalar.
#include "headingd/calib/ml/ml_reverse_scalar.hpp"
//
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "headingd/calib/ml/ml_likelihood.hpp"

namespace headingd::calib {

namespace {

using Rs = ReverseScalar;

// The 45 numbers of MlModel the EKF reads, in a fixed order: D, o, m_n, δω, Σω, Σa, Σm.
inline constexpr int kModelScalars = 45;
// The EKF's state between steps: q̃_nb (x, y, z, w) and P.
inline constexpr int kStateScalars = 13;

template <typename T, typename F>
void forEachModelScalar(MlModel<T>& m, F&& f) {
  for (int i = 0; i < 9; ++i) f(m.D.data()[i]);
  for (int i = 0; i < 3; ++i) f(m.offset(i));
  for (int i = 0; i < 3; ++i) f(m.field_n(i));
  for (int i = 0; i < 3; ++i) f(m.gyro_bias(i));
  for (int i = 0; i < 9; ++i) f(m.gyro_cov.data()[i]);
  for (int i = 0; i < 9; ++i) f(m.accel_cov.data()[i]);
  for (int i = 0; i < 9; ++i) f(m.mag_cov.data()[i]);
}

struct StoredState {
  Eigen::Quaterniond q_nb;
  Eigen::Matrix3d P;
};

// Indices on the tape of the model's and a state's scalars.
using ModelIndices = std::array<std::int32_t, kModelScalars>;
using StateIndices = std::array<std::int32_t, kStateScalars>;

StateIndices stateIndices(const MlEkf<Rs>& ekf) {
  StateIndices idx{};
  for (int i = 0; i < 4; ++i) idx[i] = ekf.attitude().coeffs()(i).index();
  for (int i = 0; i < 9; ++i) idx[4 + i] = ekf.covariance().data()[i].index();
  return idx;
}

ModelIndices modelIndices(MlModel<Rs>& model) {
  ModelIndices idx{};
  int k = 0;
  forEachModelScalar(model, [&](Rs& x) { idx[k++] = x.index(); });
  return idx;
}

}  // namespace

// Reverse mode with one checkpoint per step: a forward pass in doubles stores the EKF's
// state before every step; the backward pass then records one step at a time on a small
// tape (some 1300 nodes, which stay in the cache, where a tape of the whole run would be
// 12 MB for 400 samples and the sweep would wait on memory), with the model's 45 numbers
// and the step's 13 state numbers as its inputs, and carries d cost / d state back from
// step to step. Last, a tape of θ → model and initial state turns the accumulated adjoints
// into d cost / dθ.
bool mlCostWithAdjointGradient(const MlData& data, const double* theta, double& cost, double* gradient) {
  const MlModel<double> model = modelFromParameters<double>(theta);
  if (gradient == nullptr) return mlNegativeLogLikelihood<double>(model, data, cost);

  // Forward: the same recursion as mlNegativeLogLikelihood, keeping each step's start.
  thread_local std::vector<StoredState> states;
  const std::size_t n = data.samples.size();
  states.resize(n);
  cost = 0.0;
  {
    MlEkf<double> ekf(model, data.gravity_m_s2);
    if (!mlStartPredictor(model, data, ekf)) return false;
    for (std::size_t t = 0; t < n; ++t) {
      states[t] = StoredState{ekf.attitude(), ekf.covariance()};
      if (!mlPredictorStep(ekf, data.samples[t], cost, nullptr)) return false;
    }
    if (!std::isfinite(cost)) return false;
  }

  thread_local ReverseTape tape;
  std::array<double, kModelScalars> model_adjoint{};
  std::array<double, kStateScalars> state_adjoint{};  // d cost / d state after the step
  for (std::size_t t = n; t-- > 0;) {
    const ReverseTapeScope scope(tape);
    MlModel<Rs> step_model;
    {
      MlModel<double> values = model;
      std::array<double, kModelScalars> flat{};
      int k = 0;
      forEachModelScalar(values, [&](double& x) { flat[k++] = x; });
      k = 0;
      forEachModelScalar(step_model, [&](Rs& x) { x = Rs::variable(flat[k++]); });
    }
    const ModelIndices model_idx = modelIndices(step_model);
    MlEkf<Rs> ekf(step_model, data.gravity_m_s2);
    QuatT<Rs> q;
    for (int i = 0; i < 4; ++i) q.coeffs()(i) = Rs::variable(states[t].q_nb.coeffs()(i));
    Mat3T<Rs> P;
    for (int i = 0; i < 9; ++i) P.data()[i] = Rs::variable(states[t].P.data()[i]);
    ekf.setState(q, P);
    const StateIndices start_idx = stateIndices(ekf);
    Rs step_cost(0.0);
    mlPredictorStep(ekf, data.samples[t], step_cost, nullptr);  // succeeded in the forward pass
    const StateIndices end_idx = stateIndices(ekf);

    tape.clearAdjoints();
    tape.seed(step_cost.index(), 1.0);
    for (int i = 0; i < kStateScalars; ++i) tape.seed(end_idx[i], state_adjoint[i]);
    tape.sweepBack();
    for (int i = 0; i < kModelScalars; ++i) model_adjoint[i] += tape.adjoint(model_idx[i]);
    for (int i = 0; i < kStateScalars; ++i) state_adjoint[i] = tape.adjoint(start_idx[i]);
  }

  // θ → model and the initial state (TRIAD from D, o).
  const ReverseTapeScope scope(tape);
  std::array<Rs, kMlParameterCount> inputs;
  for (int i = 0; i < kMlParameterCount; ++i) inputs[i] = Rs::variable(theta[i]);
  MlModel<Rs> start_model = modelFromParameters<Rs>(inputs.data());
  MlEkf<Rs> ekf(start_model, data.gravity_m_s2);
  mlStartPredictor(start_model, data, ekf);
  const ModelIndices model_idx = modelIndices(start_model);
  const StateIndices start_idx = stateIndices(ekf);
  tape.clearAdjoints();
  for (int i = 0; i < kModelScalars; ++i) tape.seed(model_idx[i], model_adjoint[i]);
  for (int i = 0; i < kStateScalars; ++i) tape.seed(start_idx[i], state_adjoint[i]);
  tape.sweepBack();
  for (int i = 0; i < kMlParameterCount; ++i) gradient[i] = tape.adjoint(inputs[i].index());
  return true;
}

}  // namespace headingd::calib
