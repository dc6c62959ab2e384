#pragma once
// Kok & Schön (2016) Algorithm 1, complete: the initial estimate (step 1,
// ml_initial_estimate.hpp), then the maximum-likelihood refinement (step 2, eq. 6) of
// θ = {D, o, dip, δω, Σω, Σa, Σm} through the EKF one-step-ahead predictor (ml_ekf.hpp).
//
// K&S use numerical gradients and call step 2 computationally expensive (§5.2, §9). Here the
// gradient is exact: the cost is templated on the scalar, and by default one reverse-mode
// sweep over a tape of the EKF gives the 34 derivatives (ml_adjoint_gradient.hpp); Ceres's
// Jets (forward mode, 34 derivatives through every operation) give the same gradient more
// slowly. The minimiser is Ceres's quasi-Newton LBFGS with a Wolfe line search
// (ceres::GradientProblemSolver). Jets and numerical gradients of the same cost
// (ceres::NumericDiffFirstOrderFunction) stay selectable, to measure what each saves.
//
// No clocks here (pure like core: the same data give the same calibration): the callers
// time the two steps (prepareMaximumLikelihood, refineMaximumLikelihood) themselves.
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "headingd/calib/ml/ml_initial_estimate.hpp"
#include "headingd/calib/ml/ml_likelihood.hpp"
#include "headingd/calib/ml/ml_parameters.hpp"

namespace headingd::calib {

enum class MlGradient {
  kAdjoint,         // reverse mode on a tape (ml_adjoint_gradient.hpp), exact
  kAutomatic,       // ceres::Jet, forward mode, exact
  kNumericCentral,  // ceres::NumericDiffFirstOrderFunction, central differences (2n + 1 costs)
  kNumericForward,  // forward differences (n + 1 costs), as cheap as numerical gets
};

struct MlCalibrationOptions {
  MlInitialOptions initial;  // field norm, stationary segment, ...
  MlGradient gradient = MlGradient::kAdjoint;
  int max_iterations = 500;
  double function_tolerance = 1e-9;  // relative change of the cost that stops the search
  double gradient_tolerance = 1e-8;
  double parameter_tolerance = 1e-10;
  int lbfgs_rank = 20;
  // LBFGS can stop on a "numerical failure in line search" (its curvature pairs no longer
  // describe the cost near the steep walls of a nearly singular S_t) well before a minimum.
  // The search then starts again from the best point so far with an empty memory, up to this
  // many times, while each restart still lowers the cost.
  int max_restarts = 5;
  // The ML step's measurements thinned to every decimation-th sample, the gyro
  // pre-integrated between (MlDataOptions::decimation); step 1 always uses every sample.
  std::size_t decimation = 1;
};

struct MlProgress {
  int iteration = 0;
  double cost = 0.0;
  double gradient_max_norm = 0.0;
  double step_norm = 0.0;
  int restart = 0;  // 0 for the first search, i for the i-th restart
};
using MlProgressCallback = std::function<void(const MlProgress&)>;

struct MlCalibrationResult {
  // The ML estimate, for y_m = D m_b + o with m_b the local field in the inertial axes in µT
  // (|m_b| = field_norm_uT).
  core::Mat3 D = core::Mat3::Identity();
  core::Vec3 offset_uT = core::Vec3::Zero();
  double dip_rad = 0.0;  // below the horizon positive
  core::Vec3 gyro_bias_rad_s = core::Vec3::Zero();
  core::Vec3 gyro_sigma = core::Vec3::Zero();   // rad/s, √diag Σω
  core::Vec3 accel_sigma = core::Vec3::Zero();  // m/s²
  core::Vec3 mag_sigma = core::Vec3::Zero();    // µT
  core::Mat3 gyro_cov = core::Mat3::Identity();
  core::Mat3 accel_cov = core::Mat3::Identity();
  core::Mat3 mag_cov_uT2 = core::Mat3::Identity();
  double field_norm_uT = 0.0;
  double gravity_m_s2 = 0.0;

  MlInitialEstimate initial;  // step 1, what the refinement started from
  MlParameters theta_initial{}, theta_final{};

  double cost_initial = 0.0;  // eq. 6 at θ̂0 and at θ̂ML
  double cost_final = 0.0;
  int iterations = 0;  // summed over the restarts
  int cost_evaluations = 0;
  int gradient_evaluations = 0;
  int restarts = 0;
  // 1, or 2 when the first search ended at the dip's wall (|δ| ≈ 90°) and a second began
  // from θ̂0 with the WMM's dip (MlInitialOptions::expected_dip_rad); chosen_start 1: that one won.
  int starts = 1;
  int chosen_start = 0;
  std::string termination_first_start;  // when starts == 2
  bool converged = false;
  std::string termination;  // Ceres's message, of the last search

  // Normalised residuals of the EKF at θ̂ML and at θ̂0 (K&S §7.2, Figs. 5-6).
  std::vector<MlResidual> residuals_final;
  std::vector<MlResidual> residuals_initial;
  std::size_t samples_used = 0;
  std::size_t dropped_non_finite = 0;
  std::size_t mag_non_finite = 0;
  std::size_t time_gaps = 0;
};

// Step 1 and what step 2 needs: the initial estimate, the measurements in the problem's
// units, θ̂0 and the cost there.
struct MlProblem {
  MlInitialEstimate initial;
  MlData data;
  MlParameters theta_initial{};
  double cost_initial = 0.0;
  std::vector<MlResidual> residuals_initial;
};

// Throws CalibrationError when step 1 fails or the cost cannot be evaluated at θ̂0.
MlProblem prepareMaximumLikelihood(std::span<const core::ImuSample> samples, const MlCalibrationOptions& options);

// Step 2 from `problem` (moved into the result's initial/residuals_initial).
MlCalibrationResult refineMaximumLikelihood(MlProblem problem, const MlCalibrationOptions& options,
                                            const MlProgressCallback& progress = {});

// Both steps. Throws CalibrationError when step 1 fails or the cost cannot be evaluated at θ̂0.
MlCalibrationResult calibrateMaximumLikelihood(std::span<const core::ImuSample> samples,
                                               const MlCalibrationOptions& options,
                                               const MlProgressCallback& progress = {});

// One evaluation of eq. 6 at θ, with its gradient by `method` when `gradient` is not null.
// False when the EKF fails at θ. For the tests and the speed comparison.
bool evaluateMlCost(const MlData& data, const MlParameters& theta, MlGradient method, double& cost,
                    MlParameters* gradient);

}  // namespace headingd::calib
