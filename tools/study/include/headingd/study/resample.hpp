#pragma once
// A recording at another sample rate, as an IMU sampling at that rate would have given it:
// BROAD's 285.7 Hz trials at 50, 100, 200 or 400 Hz for the rate-independence study.
//
// Output sample k is at T_k = t_0 + k/rate. Its gyro is the mean rate over (T_{k-1}, T_k],
// taken from the attitude that the source's gyro integrates to (so a whole rotation is kept
// exactly, as an integrating gyro's output would be); accelerometer and magnetometer are the
// mean of the source samples over the same interval, each source sample held over the
// interval that ends at it (an integrate-and-dump anti-alias filter). The truth is
// interpolated (slerp) at T_k, unknown if either neighbour is; `moving` is the nearest
// source sample's. Upsampling (400 Hz from 285.7 Hz) holds the source values.
#include "headingd/study/recording.hpp"

namespace headingd::study {

// Where an accelerometer or magnetometer sample's averaging window sits: over the interval
// that ends at the sample (an integrate-and-dump sensor, whose gyro integral reaches the
// sample time while the vectors describe the interval's middle), or centred on it (a sensor
// whose vectors and integrated rates share one time).
enum class VectorWindow { kTrailing, kCentred };

Recording resample(const Recording& source, double rate_hz, VectorWindow window = VectorWindow::kTrailing);

}  // namespace headingd::study
