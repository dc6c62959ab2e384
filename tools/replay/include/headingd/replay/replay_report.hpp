#pragma once
// headingd-replay's summary on stderr: JSON lines that scripts and the golden tests read.
#include <cstddef>

#include "headingd/core/estimator.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/mag_calibration_fit.hpp"
#include "headingd/files/nmea_epochs.hpp"
#include "headingd/replay/replay_loop.hpp"

namespace headingd::replay {

// {"rows":N,<estimator counters>,"estimator_ns_per_sample":X}
void printCounters(const core::EstimatorCounters& counters, const ReplayTotals& totals);
// {"mag_calibration_set_aside":...,"mag_calibration_taken_back":...,"mag_calibration_in_use_at_end":...}
void printMagCalibration(const core::MagCalibrationFit& fit);
// {"gps_epochs":N,"gps_epochs_used_for_declination":M,"gps_values_ignored":K,"gps_dates_not_believed":D,
// "nmea_<counter>":...}
// (gps_values_ignored: values HeadingPipeline::processGps left out as unusable, as on STATUS)
void printGps(const files::NmeaEpochs& gps, const core::HeadingPipeline& pipeline);
// A warning line when the samples do not look like SI units (core/sensor_units_check.hpp).
void printSensorUnits(const core::HeadingPipeline& pipeline);

}  // namespace headingd::replay
