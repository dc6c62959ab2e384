#pragma once
// MAU: the magnetometer against the World Magnetic Model's field in the local level frame
// (Khedr, Radi & El-Sheimy, "Magnetometer-based full attitude update", M_llf ≅ R_b^llf M_b).
// While the field is clean (it matches the WMM's strength and dip: the reference tests of
// mag_disturbance.hpp pass, and the observer is using it), the field's direction observes the
// attitude about every axis but its own: with a dip of 60-75° that is mostly the tilt, which is
// what is missing under sustained acceleration (running, a vehicle), when gravity is not.
//
// The update is a ReferenceVectorModel with r the WMM's field in the filter's NED, whose north is
// magnetic (the declination is turned out later): r = F (cos I, 0, sin I). It corrects the tilt
// only; the heading's sigma is part of its innovation (the heading is the observer's, eq. 4.2).
//
// Verification through the magnetic frame (Khedr et al.): the attitude is accepted if it agrees
// with R_M^b R_z(A) R_llf^M, the body-to-magnetic-frame alignment followed by the best turn A
// about the field. The best A makes the two agree about every axis but the field's, so their
// difference is the angle between the measured field's direction and the one the corrected
// attitude predicts; the corrected attitude is kept only when that angle is below
// verify_max_rad, and otherwise the update is undone and counted.
//
// The field's error is mostly a calibration's residual, which changes slowly with the sensor's
// attitude: updates every sample at that noise would count one error many times, so the update
// comes at most once per interval_s.
#include "headingd/core/attitude_ekf.hpp"

namespace headingd::core {

struct MagneticAttitudeUpdateParams {
  double noise_uT;        // the field's error per axis against the WMM (0: MAU off)
  double interval_s;      // at most one update per this time
  double verify_max_rad;  // the magnetic-frame verification's threshold
  double max_nis;         // the innovation gate (χ², 3 degrees of freedom)
};

class MagneticAttitudeUpdate {
 public:
  explicit MagneticAttitudeUpdate(const MagneticAttitudeUpdateParams& params) : p_(params) {}

  bool enabled() const { return p_.noise_uT > 0.0; }
  // The WMM's field at the place: strength (µT) and inclination (rad, positive down).
  void setReference(double field_norm_uT, double inclination_rad);
  // One field sample (sensor axes, µT) that the observer has found clean; field_period_s: the
  // time it stands for. Returns whether the attitude was corrected.
  bool update(AttitudeEkf& ekf, const Vec3& field_uT, double field_period_s, double heading_sigma_rad);

  const FieldUpdateCounters& counters() const { return counters_; }

 private:
  MagneticAttitudeUpdateParams p_;
  bool has_reference_ = false;
  Vec3 reference_ned_uT_ = Vec3::Zero();
  double since_update_s_ = 0.0;
  FieldUpdateCounters counters_;
};

}  // namespace headingd::core
