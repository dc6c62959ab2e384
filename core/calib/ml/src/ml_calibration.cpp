#include "headingd/calib/ml/ml_calibration.hpp"

#include <ceres/autodiff_first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <ceres/iteration_callback.h>
#include <ceres/numeric_diff_first_order_function.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <utility>

#include "headingd/calib/calibration_error.hpp"
#include "headingd/calib/ml/ml_adjoint_gradient.hpp"
#include "headingd/core/angles.hpp"

namespace headingd::calib {

namespace {

// The cost without derivatives, shared by the numerical-difference wrappers.
class MlValueFunctor {
 public:
  explicit MlValueFunctor(const MlData* data) : data_(data) {}
  bool operator()(const double* theta, double* cost) const {
    return mlNegativeLogLikelihood<double>(modelFromParameters<double>(theta), *data_, *cost);
  }

 private:
  const MlData* data_;
};

// The cost with its gradient by reverse mode (ml_adjoint_gradient.hpp).
class MlAdjointFunction : public ceres::FirstOrderFunction {
 public:
  explicit MlAdjointFunction(const MlData* data) : data_(data) {}
  bool Evaluate(const double* theta, double* cost, double* gradient) const override {
    return mlCostWithAdjointGradient(*data_, theta, *cost, gradient);
  }
  int NumParameters() const override { return kMlParameterCount; }

 private:
  const MlData* data_;
};

std::unique_ptr<ceres::FirstOrderFunction> makeFunction(const MlData* data, MlGradient method) {
  switch (method) {
    case MlGradient::kNumericCentral:
      return std::make_unique<ceres::NumericDiffFirstOrderFunction<MlValueFunctor, ceres::CENTRAL, kMlParameterCount>>(
          new MlValueFunctor(data));
    case MlGradient::kNumericForward:
      return std::make_unique<ceres::NumericDiffFirstOrderFunction<MlValueFunctor, ceres::FORWARD, kMlParameterCount>>(
          new MlValueFunctor(data));
    case MlGradient::kAdjoint: return std::make_unique<MlAdjointFunction>(data);
    case MlGradient::kAutomatic:
    default:
      return std::make_unique<ceres::AutoDiffFirstOrderFunction<MlCostFunctor, kMlParameterCount>>(
          new MlCostFunctor(data));
  }
}

class ProgressForwarder : public ceres::IterationCallback {
 public:
  ProgressForwarder(const MlProgressCallback& cb, const int& restart) : cb_(cb), restart_(restart) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (cb_) {
      MlProgress p;
      p.iteration = s.iteration;
      p.cost = s.cost;
      p.gradient_max_norm = s.gradient_max_norm;
      p.step_norm = s.step_norm;
      p.restart = restart_;
      cb_(p);
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const MlProgressCallback& cb_;
  const int& restart_;
};

// Within a degree of ±90° the dip is at the wall of its domain.
constexpr double kDipWall_rad = 89.0 * core::kRadPerDeg;

core::Vec3 sigmas(const core::Mat3& cov) { return cov.diagonal().cwiseMax(0.0).cwiseSqrt(); }

}  // namespace

bool evaluateMlCost(const MlData& data, const MlParameters& theta, MlGradient method, double& cost,
                    MlParameters* gradient) {
  const auto f = makeFunction(&data, method);
  return f->Evaluate(theta.data(), &cost, gradient ? gradient->data() : nullptr);
}

MlProblem prepareMaximumLikelihood(std::span<const core::ImuSample> samples, const MlCalibrationOptions& options) {
  MlProblem p;
  p.initial = estimateInitialParameters(samples, options.initial);
  MlDataOptions data_options;
  data_options.field_norm_uT = options.initial.field_norm_uT;
  data_options.gravity_m_s2 = p.initial.gravity_m_s2;
  data_options.initial_average_samples = options.initial.initial_average_samples;
  data_options.expected_dip_sign = options.initial.expected_dip_sign;
  data_options.decimation = std::max<std::size_t>(options.decimation, 1);
  p.data = prepareMlData(samples, data_options);
  p.theta_initial = packParameters(initialParameterValues(p.initial, options.initial));
  if (!mlNegativeLogLikelihood<double>(modelFromParameters<double>(p.theta_initial.data()), p.data, p.cost_initial,
                                       &p.residuals_initial)) {
    throw CalibrationError(
        "the EKF cannot run with the initial estimate (an innovation covariance is not "
        "positive definite, the cost is not finite, or the dip has the sign the place rules out)");
  }
  return p;
}

MlCalibrationResult refineMaximumLikelihood(MlProblem problem, const MlCalibrationOptions& options,
                                            const MlProgressCallback& progress) {
  MlCalibrationResult out;
  const MlData& data = problem.data;
  out.initial = std::move(problem.initial);
  out.field_norm_uT = out.initial.field_norm_uT;
  out.gravity_m_s2 = out.initial.gravity_m_s2;
  out.samples_used = data.samples.size();
  out.dropped_non_finite = data.dropped_non_finite;
  out.mag_non_finite = data.mag_non_finite;
  out.time_gaps = data.time_gaps;
  out.theta_initial = problem.theta_initial;
  out.cost_initial = problem.cost_initial;
  out.residuals_initial = std::move(problem.residuals_initial);

  ceres::GradientProblem gradient_problem(makeFunction(&data, options.gradient).release());
  ceres::GradientProblemSolver::Options solver_options;
  solver_options.line_search_direction_type = ceres::LBFGS;
  solver_options.line_search_type = ceres::WOLFE;
  solver_options.max_lbfgs_rank = options.lbfgs_rank;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.logging_type = ceres::SILENT;
  // Ceres keeps the start when a search ends in FAILURE; this keeps its last accepted point.
  solver_options.update_state_every_iteration = true;
  int restart = 0;
  ProgressForwarder forwarder(progress, restart);
  solver_options.callbacks.push_back(&forwarder);

  // One search from `theta` (cost `cost`), with restarts after a line-search failure;
  // `theta` and `cost` end at the best point reached, never worse than the start.
  const auto search = [&](MlParameters& theta, double& cost) {
    for (;; ++restart) {
      solver_options.max_num_iterations = std::max(options.max_iterations - out.iterations, 0);
      const MlParameters start = theta;
      ceres::GradientProblemSolver::Summary summary;
      ceres::Solve(solver_options, gradient_problem, theta.data(), &summary);
      out.iterations += std::max(static_cast<int>(summary.iterations.size()) - 1, 0);
      out.cost_evaluations += summary.num_cost_evaluations;
      out.gradient_evaluations += summary.num_gradient_evaluations;
      out.converged = summary.termination_type == ceres::CONVERGENCE;
      out.termination = summary.message;
      double reached = 0.0;
      if (!mlNegativeLogLikelihood<double>(modelFromParameters<double>(theta.data()), data, reached) ||
          !(reached <= cost)) {
        theta = start;
        return;
      }
      const bool improved = cost - reached > options.function_tolerance * std::abs(cost);
      cost = reached;
      if (summary.termination_type != ceres::FAILURE || !improved || restart >= options.max_restarts ||
          out.iterations >= options.max_iterations) {
        return;
      }
      out.restarts = restart + 1;
    }
  };
  // The search can run into the wall at |dip| = 90° (the mirror beyond it, ml_likelihood.hpp):
  // from an initial estimate ~90° off in heading the path of steepest descent leads through
  // a vertical field, where heading is free. Stopped there it is no estimate at all.
  const auto atDipWall = [](const MlParameters& theta) { return std::abs(theta[ml_index::kDip]) > kDipWall_rad; };

  MlParameters theta = out.theta_initial;
  double cost = out.cost_initial;
  search(theta, cost);
  if (atDipWall(theta) && options.initial.expected_dip_rad) {
    // Second start: θ̂0 with the WMM's dip instead of eq. 28b's (which is some 10° low in the
    // K&S §8 runs that hit the wall); the lower cost off the wall wins.
    MlParameters second = out.theta_initial;
    second[ml_index::kDip] = *options.initial.expected_dip_rad;
    double second_cost = 0.0;
    if (mlNegativeLogLikelihood<double>(modelFromParameters<double>(second.data()), data, second_cost)) {
      ++out.starts;
      out.termination_first_start = out.termination;
      const bool first_converged = out.converged;
      search(second, second_cost);
      if (!atDipWall(second) || second_cost < cost) {
        theta = second;
        cost = second_cost;
        out.chosen_start = 1;
      } else {
        out.converged = first_converged;
        out.termination = out.termination_first_start;
      }
    }
  }

  if (atDipWall(theta)) {
    out.converged = false;
    out.termination += " (ended at the dip's +-90 deg wall: the field direction is not determined)";
  }

  double final_cost = 0.0;
  if (!mlNegativeLogLikelihood<double>(modelFromParameters<double>(theta.data()), data, final_cost,
                                       &out.residuals_final) ||
      !(final_cost <= out.cost_initial)) {
    // Never hand back something worse than the start.
    theta = out.theta_initial;
    mlNegativeLogLikelihood<double>(modelFromParameters<double>(theta.data()), data, final_cost, &out.residuals_final);
    out.converged = false;
    out.termination += " (kept the initial estimate)";
  }
  out.theta_final = theta;
  out.cost_final = final_cost;

  const MlParameterValues v = unpackParameters(theta);
  const double f = out.field_norm_uT;
  out.D = v.D;
  out.offset_uT = v.offset * f;
  out.dip_rad = v.dip_rad;
  out.gyro_bias_rad_s = v.gyro_bias_rad_s;
  out.gyro_cov = v.gyro_cov;
  out.accel_cov = v.accel_cov;
  out.mag_cov_uT2 = v.mag_cov * f * f;
  out.gyro_sigma = sigmas(out.gyro_cov);
  out.accel_sigma = sigmas(out.accel_cov);
  out.mag_sigma = sigmas(out.mag_cov_uT2);
  return out;
}

MlCalibrationResult calibrateMaximumLikelihood(std::span<const core::ImuSample> samples,
                                               const MlCalibrationOptions& options,
                                               const MlProgressCallback& progress) {
  return refineMaximumLikelihood(prepareMaximumLikelihood(samples, options), options, progress);
}

}  // namespace headingd::calib
