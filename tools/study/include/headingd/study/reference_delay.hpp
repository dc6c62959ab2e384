#pragma once
// How late a recording's magnetometer and gyro are against its reference attitude, measured
// with the reference itself (a check of the estimator's learned delay, vector_delay_estimator.hpp,
// that does not use the estimator):
//  - the field: a constant earth field read Δ late, turned into the earth frame by the
//    reference at the sample's time, swings with every turn; the Δ that makes it steadiest
//    (its spread after a 0.5 s moving mean is taken out, so that a room's field varying along
//    the path and a calibration's residual do not count) is the magnetometer's delay;
//  - the gyro: the shift that best matches its rate to the rate between consecutive
//    reference attitudes (an interval-mean gyro is half a sample late).
// Both by a search over whole milliseconds, the samples interpolated linearly.
#include "headingd/study/recording.hpp"

namespace headingd::study {

struct ReferenceDelays {
  double mag_s = 0.0;                  // the field reads the reference attitude of this long before
  double mag_spread_uT = 0.0;          // the field's spread at that delay
  double mag_spread_at_zero_uT = 0.0;  // ... and without one
  double gyro_s = 0.0;                 // the gyro's rate is the reference's of this long before
  bool valid = false;                  // enough samples with a reference
};

// Searches mag delays in [min_s, max_s] and gyro shifts in ±20 ms.
ReferenceDelays measureReferenceDelays(const Recording& r, double min_s = -0.05, double max_s = 0.08);

}  // namespace headingd::study
