#include "headingd/replay/replay_report.hpp"

#include <cstdio>

namespace headingd::replay {

void printCounters(const core::EstimatorCounters& c, const ReplayTotals& totals) {
  std::fprintf(stderr, "{\"rows\":%zu", totals.rows);
  core::forEachCounter(c, [](const char* name, std::uint64_t v) {
    std::fprintf(stderr, ",\"%s\":%llu", name, static_cast<unsigned long long>(v));
  });
  const double ns = static_cast<double>(totals.estimator_time.count());
  std::fprintf(stderr, ",\"estimator_ns_per_sample\":%.1f}\n",
               totals.rows ? ns / static_cast<double>(totals.rows) : 0.0);
}

void printMagCalibration(const core::MagCalibrationFit& fit) {
  std::fprintf(stderr,
               "{\"mag_calibration_set_aside\":%llu,\"mag_calibration_taken_back\":%llu,"
               "\"mag_calibration_in_use_at_end\":%s}\n",
               static_cast<unsigned long long>(fit.setAside()), static_cast<unsigned long long>(fit.takenBack()),
               fit.calibrationInUse() ? "true" : "false");
}

void printSensorUnits(const core::HeadingPipeline& pipeline) {
  const std::string units = pipeline.sensorUnits().describe();
  if (!units.empty())
    std::fprintf(stderr, "headingd-replay: warning: IMU samples not in SI units? %s\n", units.c_str());
}

void printGps(const files::NmeaEpochs& gps, const core::HeadingPipeline& pipeline) {
  std::fprintf(stderr,
               "{\"gps_epochs\":%zu,\"gps_epochs_used_for_declination\":%llu,\"gps_values_ignored\":%llu,"
               "\"gps_dates_not_believed\":%llu",
               gps.epochs.size(), static_cast<unsigned long long>(pipeline.gpsEpochsUsedForDeclination()),
               static_cast<unsigned long long>(pipeline.gpsValuesIgnored()),
               static_cast<unsigned long long>(pipeline.gpsDatesNotBelieved()));
  nmea::forEachCounter(gps.counters, [](const char* name, std::uint64_t v) {
    std::fprintf(stderr, ",\"nmea_%s\":%llu", name, static_cast<unsigned long long>(v));
  });
  std::fputs("}\n", stderr);
}

}  // namespace headingd::replay
