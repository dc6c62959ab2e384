#pragma once
// The --report DIR page: magnetometer data before and after calibration (projections and
// norm over time, as Kok & Schön 2016 Figs. 1, 3, 4), normalised residuals against N(0,1)
// (Figs. 5, 6) and a verdict in words (coverage of the sphere, residual whiteness,
// condition of the problem). Writes DIR/index.html (plots inline as SVG).
#include <string>
#include <vector>

#include "headingd/core/imu_calibration.hpp"

namespace headingd::calibrate {

struct ReportInput {
  std::string method;
  std::string source_file;
  std::vector<double> t_s;  // per magnetometer sample
  std::vector<core::Vec3> mag_raw_uT;
  core::ImuCalibration calibration;
  // Normalised residuals (dimensionless, N(0,1) if the model and noise levels are right).
  std::vector<double> residuals;
  std::string residual_kind;  // what the residuals are, for the caption
  double coverage = 0.0;
  double condition_number = 0.0;
  std::vector<std::string> notes;  // extra lines (timings, segments found, ...)
};

struct Verdict {
  std::string coverage, whiteness, condition, overall;
  double lag1_autocorrelation = 0.0;
  double residual_mean = 0.0, residual_std = 0.0;
};
Verdict judge(const ReportInput& in);

// Throws std::runtime_error if the directory or file cannot be written.
void writeReport(const std::string& dir, const ReportInput& in);

}  // namespace headingd::calibrate
