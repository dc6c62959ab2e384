#pragma once
// The QSF update (Renaudin & Combettes 2014, eqs. 35-38): during a quasi-static period of the
// magnetic field (quasi_static_field.hpp) the field is constant in the navigation frame, whatever
// its value, so its value at the period's start, turned into NED by the attitude then, is a
// reference for the attitude for as long as the period lasts. Indoors, by steel furniture or a
// radiator, the field is wrong but static: the observer sets it aside (eq. 4.3) and the heading
// runs on the gyro; this update holds the heading to where the period began instead of letting
// the gyro's error move it.
//
// A ReferenceVectorModel with r the period's reference, correcting the heading only (the tilt is
// gravity's; its uncertainty is part of the innovation). Used only while the observer sets the
// field aside: a clean field already corrects the heading, and a second correction from the same
// samples would count them twice.
//
// What it observes is the heading's change since the period began (an error the heading had then
// is in the reference too), so its prior is the drift the gyro can have made since: the rate error
// about the vertical that the bias filter allows, times the time since the last update, added to
// the sigma that update left (a bias's drift grows linearly, not as a random walk). A field that moved
// further than that (a gradient walked through, a magnet fixed to the sensor while it turns
// slowly: both pass the detector's window for a long time) fails the innovation gate, and the
// correction is never larger than what the gyro could have drifted. With the heading's whole
// sigma as its prior instead (tens of degrees after a disturbance) the update followed such
// fields: BROAD's attached magnet at 3 cm 2.18° → 3.99°, all 14 trials 1.25° → 1.59°.
//
// Only while the person stands: the motion level says "standing" (§3.1) and the specific force is
// quasi-static too (quasi_static_field.hpp; a walk's steps move it well beyond its 0.1 m/s²).
// Walking carries the sensor through the field's gradients indoors, and a field that changes
// slowly with position passes the detector's one-second window for as long as the walk lasts, so
// that a period's start is no reference at its end. With neither condition, the simulated urban
// walk's consumer grade went from 8.42° to 14.7° (6 seeds, 100 Hz); with the level alone, a
// texting phone walking past magnets (whose level never leaves "standing") lost 3.64 → 4.43°
// (the shared nexus5_magnets texting trial), every shared phone group lost, and the specific
// force's test keeps the update out of all of them.
//
// Its noise is the sample's white noise and, once the sensor has turned within the period, a
// calibration's residual hard iron: fixed in sensor axes, it moves in the navigation frame by
// |b| per radian the sensor turns, which the period's reference does not know (the same allowance
// as the strength test's, mag_disturbance.hpp). Without it the update takes that residual into the
// heading: on BROAD's slow rotations (trial 03) 1.20° became 3.99° with 1 µT of white noise alone.
#include "headingd/core/attitude_ekf.hpp"

namespace headingd::core {

struct QuasiStaticFieldUpdateParams {
  double noise_uT;               // the field's white noise per axis and sample (0: the update is off)
  double residual_hard_iron_uT;  // per radian turned since the period's start, added to the noise
  double max_nis;                // the innovation gate (χ², 3 degrees of freedom)
};

class QuasiStaticFieldUpdate {
 public:
  explicit QuasiStaticFieldUpdate(const QuasiStaticFieldUpdateParams& params) : p_(params) {}

  bool enabled() const { return p_.noise_uT > 0.0; }
  // One new field sample (sensor axes, µT): in_period whether the field is quasi-static now
  // (the detector's verdict for this sample) and the person stands, set_aside whether the observer
  // has not used it.
  // field_period_s: the time since the previous field sample; rate_sigma_rad_s: the sigma of the
  // gyro's rate error about the vertical. Returns the heading turn applied (rad about NED down;
  // 0 if none).
  // gyro_frame_from_sensor: the sensor's attitude in a frame the bias-corrected gyro alone
  // carries (the detectors' GyroFrame).
  double update(AttitudeEkf& ekf, const Vec3& field_uT, const Quat& gyro_frame_from_sensor, bool in_period,
                bool set_aside, double field_period_s, double rate_sigma_rad_s);
  // After a gap: the period's reference no longer holds.
  void restart() { has_reference_ = false; }

  const FieldUpdateCounters& counters() const { return counters_; }

 private:
  QuasiStaticFieldUpdateParams p_;
  bool has_reference_ = false;
  Vec3 reference_ned_uT_ = Vec3::Zero();
  Quat start_attitude_ = Quat::Identity();    // the sensor's at the period's start
  Quat start_gyro_frame_ = Quat::Identity();  // its attitude in the gyro's frame then
  double heading_corrected_rad_ = 0.0;        // turned by this update since the start
  double drift_sigma_rad_ = 0.0;              // of the heading's change since then
  FieldUpdateCounters counters_;
};

}  // namespace headingd::core
