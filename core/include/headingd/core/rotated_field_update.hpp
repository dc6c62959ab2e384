#pragma once
// MARU and AGU, Renaudin & Combettes (2014): the magnetic angular rate update (eqs. 39-43) and
// the acceleration gradient update (eqs. 44-46). During a quasi-static period of a field
// (quasi_static_field.hpp: the magnetic field, or the specific force) the field is constant in
// the navigation frame whatever its value, so its change in sensor axes is the sensor's rotation
// alone, and what the gyro says of that rotation is off by its bias: the pair of samples at the
// two ends of a baseline observes the gyro's bias (RotatedVectorModel over a
// GyroRotationIntegral, rotated_vector_model.hpp), which the bias filter takes as one more
// measurement (GyroBiasEstimator::addMeasurement). It observes the bias across the field's
// direction in sensor axes. A disturbed field indoors that is static points elsewhere than the
// earth's, so MARU there also sees what the heading observer, which sets such a field aside,
// cannot: the bias about the vertical. AGU's field is gravity while the person stands, which
// observes what the gravity update's turns already do (the bias across the vertical); its
// accelerometer-bias part (eq. 44's b_a) is not taken: the accelerometer's bias is not a state of
// this estimator, and its effect is in the noise below instead.
//
// Why a baseline of seconds and not MAGYQ's one sample: the rotation a bias error causes grows
// with the time, the two samples' noise does not (rotated_vector_model.hpp). Successive
// baselines share no interval (each starts where the last ended), so no interval is counted
// twice, and a correction of the bias never feeds back into a baseline still running on the bias
// before it.
//
// The caller says when it applies (estimator.cpp: the field quasi-static, the person standing,
// the sensor not at rest, where still blocks measure the bias from the gyro itself).
//
// The noise: each sample's white noise as the detector's window shows it (never below
// min_sample_noise), and a residual per radian the sensor turned over the baseline: what is fixed
// in sensor axes (a calibration's residual hard iron, an accelerometer's bias) turns with the
// sensor and looks like a rotation the gyro did not make. The innovation gate rejects a baseline
// over which the field moved after all.
#include "headingd/core/attitude_ekf.hpp"
#include "headingd/core/gyro_bias_estimator.hpp"
#include "headingd/core/rotated_vector_model.hpp"

namespace headingd::core {

struct RotatedFieldUpdateParams {
  double baseline_s;        // the interval between a measurement's two samples (0: off)
  double residual_per_rad;  // fixed in sensor axes, per radian turned over the baseline (field unit)
  double min_sample_noise;  // the least white noise per axis a sample is taken to have (field unit)
  double max_nis;           // the innovation gate (χ², 3 degrees of freedom)
};

class RotatedFieldUpdate {
 public:
  explicit RotatedFieldUpdate(const RotatedFieldUpdateParams& params) : p_(params) {}

  bool enabled() const { return p_.baseline_s > 0.0; }
  // Every gyro sample: the sensor's attitude in the frame the bias-corrected gyro carries
  // (GyroFrame) and the time since the previous sample.
  void advance(const Quat& gyro_frame_from_sensor, double dt_s) {
    if (running_) integral_.add(gyro_frame_from_sensor, dt_s);
  }
  // One new sample of the field (sensor axes) with the same frame: applies: whether the update
  // applies now (see the top); sample_noise: the field's white noise per axis (the detector's
  // window). Returns whether the bias was corrected.
  bool update(GyroBiasEstimator& bias, const Vec3& field, const Quat& gyro_frame_from_sensor, bool applies,
              double sample_noise);
  // After a gap: the gyro frame does not reach across it.
  void restart() { running_ = false; }

  const FieldUpdateCounters& counters() const { return counters_; }

 private:
  void startBaseline(const Vec3& field, double noise, const Quat& gyro_frame_from_sensor);

  RotatedFieldUpdateParams p_;
  bool running_ = false;
  Vec3 start_field_ = Vec3::Zero();  // the baseline's first sample
  double start_noise_ = 0.0;         // and its window's noise
  GyroRotationIntegral integral_;
  FieldUpdateCounters counters_;
};

}  // namespace headingd::core
