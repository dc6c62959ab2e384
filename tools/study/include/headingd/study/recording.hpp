#pragma once
// A recording to study the estimator on: IMU samples with the true attitude beside them,
// from a BROAD trial or a simulator run, on one convention: truth_nb maps sensor axes to NED
// with *magnetic* north (what the estimator estimates without a GPS), NaN where unknown.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "headingd/core/imu_sample.hpp"
#include "headingd/sim/simulation.hpp"

namespace headingd::study {

struct Recording {
  std::string name;
  double rate_hz = 0.0;
  std::vector<core::ImuSample> samples;
  std::vector<core::Quat> truth_nb;  // one per sample; NaN coefficients where unknown
  std::vector<bool> moving;          // the samples that are scored (BROAD's `moving`)
  // The World Magnetic Model's field where it was recorded (a simulation's place), given to the
  // estimator as the daemon gives it with a GPS fix (Estimator::setReferenceField); 0: none.
  double reference_field_uT = 0.0;
  double reference_inclination_rad = 0.0;

  std::size_t size() const { return samples.size(); }
};

// A BROAD trial (format: tests/data/broad/README.md): its ENU reference turned into NED.
Recording readBroadTrial(const std::string& path);

// A simulator run: the true sensor attitude with the declination taken out of its heading.
Recording fromSimulation(const sim::SimResult& result, std::string name);

// Turns the first sample's accelerometer and magnetometer by angle_rad about an axis drawn
// from seed (perpendicular to gravity's direction when angle_rad is the whole tilt), so that
// an estimator that starts from the first sample starts that far off.
void startOffBy(Recording& r, double angle_rad, std::uint64_t seed);

// The true attitude, NaN quaternion for "unknown".
inline bool hasTruth(const core::Quat& q) { return q.coeffs().allFinite(); }

// The reference's rate from sample i to i + 1, in the sensor's axes (rad/s): the turn between
// the two true attitudes over the time between them (q and -q alike). NaN where either is
// unknown or the time does not advance.
core::Vec3 referenceRate(const Recording& r, std::size_t i);

}  // namespace headingd::study
