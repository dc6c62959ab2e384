#include "headingd/calib/ml_calibration.hpp"

#include <ceres/autodiff_first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <ceres/iteration_callback.h>
#include <ceres/numeric_diff_first_order_function.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "headingd/calib/calibration_error.hpp"

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

std::unique_ptr<ceres::FirstOrderFunction> makeFunction(const MlData* data, MlGradient method) {
  switch (method) {
    case MlGradient::kNumericCentral:
      return std::make_unique<ceres::NumericDiffFirstOrderFunction<MlValueFunctor, ceres::CENTRAL, kMlParameterCount>>(
          new MlValueFunctor(data));
    case MlGradient::kNumericForward:
      return std::make_unique<ceres::NumericDiffFirstOrderFunction<MlValueFunctor, ceres::FORWARD, kMlParameterCount>>(
          new MlValueFunctor(data));
    case MlGradient::kAutomatic:
    default:
      return std::make_unique<ceres::AutoDiffFirstOrderFunction<MlCostFunctor, kMlParameterCount>>(
          new MlCostFunctor(data));
  }
}

class ProgressForwarder : public ceres::IterationCallback {
 public:
  explicit ProgressForwarder(const MlProgressCallback& cb) : cb_(cb) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (cb_) {
      MlProgress p;
      p.iteration = s.iteration;
      p.cost = s.cost;
      p.gradient_max_norm = s.gradient_max_norm;
      p.step_norm = s.step_norm;
      p.seconds = s.cumulative_time_in_seconds;
      cb_(p);
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const MlProgressCallback& cb_;
};

core::Vec3 sigmas(const core::Mat3& cov) { return cov.diagonal().cwiseMax(0.0).cwiseSqrt(); }

}  // namespace

bool evaluateMlCost(const MlData& data, const MlParameters& theta, MlGradient method, double& cost,
                    MlParameters* gradient) {
  const auto f = makeFunction(&data, method);
  return f->Evaluate(theta.data(), &cost, gradient ? gradient->data() : nullptr);
}

MlCalibrationResult calibrateMaximumLikelihood(std::span<const core::ImuSample> samples,
                                               const MlCalibrationOptions& options,
                                               const MlProgressCallback& progress) {
  // Elapsed time is measured for the report only; it never changes a result.
  const auto start = std::chrono::steady_clock::now();
  MlCalibrationResult out;
  out.initial = estimateInitialParameters(samples, options.initial);
  out.field_norm_uT = out.initial.field_norm_uT;
  out.gravity_m_s2 = out.initial.gravity_m_s2;

  MlDataOptions data_options;
  data_options.field_norm_uT = options.initial.field_norm_uT;
  data_options.gravity_m_s2 = out.gravity_m_s2;
  data_options.initial_average_samples = options.initial.initial_average_samples;
  const MlData data = prepareMlData(samples, data_options);
  out.samples_used = data.samples.size();
  out.dropped_non_finite = data.dropped_non_finite;
  out.mag_non_finite = data.mag_non_finite;
  out.time_gaps = data.time_gaps;

  out.theta_initial = packParameters(initialParameterValues(out.initial, options.initial));
  if (!mlNegativeLogLikelihood<double>(modelFromParameters<double>(out.theta_initial.data()), data,
                                       out.cost_initial, &out.residuals_initial)) {
    throw CalibrationError("the EKF cannot run with the initial estimate (an innovation covariance is not "
                           "positive definite or the cost is not finite)");
  }

  const auto ml_start = std::chrono::steady_clock::now();
  ceres::GradientProblem problem(makeFunction(&data, options.gradient).release());
  ceres::GradientProblemSolver::Options solver_options;
  solver_options.line_search_direction_type = ceres::LBFGS;
  solver_options.line_search_type = ceres::WOLFE;
  solver_options.max_lbfgs_rank = options.lbfgs_rank;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.logging_type = ceres::SILENT;
  ProgressForwarder forwarder(progress);
  solver_options.callbacks.push_back(&forwarder);
  ceres::GradientProblemSolver::Summary summary;
  MlParameters theta = out.theta_initial;
  ceres::Solve(solver_options, problem, theta.data(), &summary);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - ml_start).count();

  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.cost_evaluations = summary.num_cost_evaluations;
  out.gradient_evaluations = summary.num_gradient_evaluations;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.termination = summary.message;

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
  out.seconds_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace headingd::calib
