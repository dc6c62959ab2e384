#pragma once
// One receiver epoch (nmea::Fix) as the estimator's GpsObservation, stamped `t_ns` on the
// IMU's time axis. The one conversion used by every GPS input: NMEA captures read whole
// (nmea_epochs.hpp), the daemon's serial receiver and its NMEA log player.
#include <cstdint>

#include "headingd/core/gps_observation.hpp"
#include "headingd/nmea/fix.hpp"

namespace headingd::nmea {

// fix_ok needs a position and a mode other than "no fix"; the height is above the ellipsoid
// (MSL + geoid separation, in km as the WMM wants it); the decimal year (WMM epoch) comes from
// the UTC date when the receiver sent one; course and variation in rad.
core::GpsObservation gpsObservationFromFix(const nmea::Fix& fix, std::int64_t t_ns);

}  // namespace headingd::nmea
