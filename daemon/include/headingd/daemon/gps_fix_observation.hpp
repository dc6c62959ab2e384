#pragma once
// One receiver epoch (nmea::Fix) as the estimator's GpsObservation, stamped `t_ns` on the
// IMU's time axis (for live sources: the monotonic receive time of the epoch's last byte).
#include <cstdint>

#include "headingd/core/gps_observation.hpp"
#include "headingd/nmea/fix.hpp"

namespace headingd::daemon {

core::GpsObservation gpsObservationFromFix(const nmea::Fix& fix, std::int64_t t_ns);

}  // namespace headingd::daemon
