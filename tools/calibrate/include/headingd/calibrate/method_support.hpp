#pragma once
// Steps that more than one calibration method of headingd-calibrate takes.
#include <optional>
#include <span>
#include <vector>

#include "headingd/calib/ml/ml_initial_estimate.hpp"
#include "headingd/calibrate/methods.hpp"
#include "headingd/core/imu_calibration.hpp"

namespace headingd::calibrate {

// Without a field norm from the arguments or the WMM: the one that gives the ellipsoid fit's
// D a unit determinant, and a `field.detail` that says so.
void takeFieldNormFromDataIfUnknown(FieldNorm& field, std::span<const core::Vec3> mags);

// The dip's sign and value known from the place, for the misalignment step.
void applyPlace(calib::MlInitialOptions& o, calib::DipSign dip_sign, const FieldNorm& field);

// Radial residuals (|m_b| − F)/σ of the calibrated field, for the report.
std::vector<double> radialResiduals(const core::ImuCalibration& cal, std::span<const core::Vec3> mags, double sigma_uT);

// The field's noise at rest carried through D⁻¹ (per axis), or `fallback` without a
// measured noise.
double restSigmaCalibrated(const core::ImuCalibration& cal, const std::optional<core::Vec3>& mag_sigma_raw,
                           double fallback);

// How much of the sphere the calibrated field's directions cover (calib::sphereCoverage).
double calibratedCoverage(const core::ImuCalibration& cal, std::span<const core::Vec3> mags);

}  // namespace headingd::calibrate
