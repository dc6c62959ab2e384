#pragma once
// Magnetic disturbance detection for the gain K of Henriksson eq. 4.2 (§4.2): K = 0 while
// the field is disturbed, so the heading runs on the gyro alone (eq. 4.3).
//
// Two tests, each against a low-pass of the same quantity (so that a building that weakens
// the field for minutes is accepted again once the low-pass has followed it, as §4.2 asks):
//  - field strength: Δm = ||m| - |m_lp|| (eq. 4.5);
//  - dip angle: a disturbance that keeps the strength but turns the field changes the angle
//    between the field and gravity, which a clean Earth field keeps constant.
// Once the position is known (GPS + World Magnetic Model), two absolute tests join them:
//  - field strength against the model's total intensity F at that place;
//  - dip angle against the model's inclination.
// Indoors a building may weaken the field for minutes while its direction stays right
// (§4.2); the absolute strength test is therefore wider than the relative one.
//
// The two relative tests compare single samples, so their thresholds must sit above the
// magnetometer's own noise: each is the configured value or 4 times the learned noise floor
// of that deviation (noise_floor.hpp), whichever is larger (at most 5 times the configured;
// that most until the floor is known, in the first 2 s).
// And the strength test allows for a calibration's residual hard iron h: as the sensor turns
// by an angle θ against the field, the strength it measures changes by up to |h| θ, so the
// threshold grows by residual_hard_iron_uT × θ, θ the angle between the field's direction
// low-passed in the sensor's axes and low-passed in a frame that turns with the gyro (both
// over time_constant_s: a disturbance moves both alike, the sensor's own turning only the
// first). A phone swung in the hand or carried in a pocket otherwise has 7-21 % of the
// samples of an undisturbed walk flagged; a building's field, met while walking straight on,
// still is.
//
// A strong passing disturbance (a magnet on the path: hundreds of µT for a few seconds) drags
// the low-passes far away, and after it they take ln(excursion / threshold) time constants to
// come back (a 300 µT spike, 13-16 s): the field is back long before the tests say so. So the
// low-passes' strength and dip are remembered while the tests have passed for
// back_to_before_s, and a field that is back within both thresholds of them for as long is
// clean again, the low-passes restarting there. A lasting change (a magnet attached, a
// building) that never returns is still accepted only once the low-passes have followed it;
// a field that passes through the old values as it turns does not stay there.
//
// Without a position there is no model to test the strength and dip against, and the relative
// tests accept a lasting change once the low-passes have followed it (a few time constants):
// standing in a lift's steel cabin, the heading follows its field after some seconds. So the
// field's strength and dip are learned instead, as VQF learns its reference: from the low-passes
// once the field has been clean for learn_first_s, then following them slowly (over learn_new_s)
// while they stay within the reference thresholds; a field outside them is disturbed by the
// same two absolute tests as against the WMM, and becomes the learned field only once it has
// been homogeneous (the relative tests passing) for learn_new_s without a break. A WMM
// reference replaces the learned one.
#include "headingd/core/gyro_frame_low_pass.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/noise_floor.hpp"

namespace headingd::core {

struct MagDisturbanceParams {
  double time_constant_s;  // low-pass of strength and dip (§4.2: about 3 s)
  double max_norm_deviation_uT;
  double max_dip_deviation_rad;
  double max_reference_norm_deviation_uT;  // |low-passed ‖m‖ - F_WMM|
  double max_reference_dip_deviation_rad;  // |low-passed dip - I_WMM|
  double back_to_before_s;                 // 0: the low-passes alone decide (see above)
  double residual_hard_iron_uT = 0.0;      // per rad turned: the strength test's allowance
  double learn_first_s = 0.0;              // clean this long: the first learned field (0: nothing learned)
  double learn_new_s = 0.0;                // homogeneous this long: a different field is learned
};

// Which tests found the sample disturbed (several may).
struct MagDisturbance {
  bool norm_jump = false;       // eq. 4.5 against the low-pass
  bool dip_jump = false;        // dip against its low-pass
  bool norm_reference = false;  // strength against the WMM
  bool dip_reference = false;   // dip against the WMM inclination
  bool any() const { return norm_jump || dip_jump || norm_reference || dip_reference; }
};

class MagDisturbanceDetector {
 public:
  explicit MagDisturbanceDetector(const MagDisturbanceParams& p)
      : p_(p),
        norm_lp_(p.time_constant_s),
        dip_lp_(p.time_constant_s),
        norm_deviation2_(1.0),
        dip_deviation2_(1.0),
        norm_floor_(2.0),
        dip_floor_(2.0),
        direction_gyro_frame_(p.time_constant_s),
        direction_sensor_axes_(p.time_constant_s) {}

  // The tests for one field sample (sensor axes) and its dip against gravity, with the
  // strength test's allowance for the angle the sensor has turned against the field. Call
  // advance() with every gyro increment, also between field samples, and restart() after a gap
  // in the samples.
  MagDisturbance update(const Vec3& field_uT, double dip_rad, double dt_s);
  void advance(const Quat& gyro_increment) {
    if (p_.residual_hard_iron_uT > 0.0) direction_gyro_frame_.advance(gyro_increment);
  }
  void restart();
  // The angle by which the sensor had turned against the field at the last update (rad);
  // measured only where the strength test needed it (0 otherwise).
  double turnedRad() const { return turned_rad_; }

  // The Earth's field at the current place (WMM): total intensity and inclination.
  void setReference(double field_norm_uT, double inclination_rad);
  bool hasReference() const { return has_reference_; }
  // Whether the strength and dip tested against are learned ones (no WMM reference yet).
  bool hasLearnedReference() const { return !has_reference_ && has_learned_; }
  double normDeviation() const { return norm_deviation_; }
  double dipDeviation() const { return dip_deviation_; }

 private:
  // The tests; the strength's allowance from the directions the update just took, if it took them.
  MagDisturbance test(double field_norm_uT, double dip_rad, double dt_s, bool has_directions);
  double turnedAgainstField() const;
  // The absolute tests against the WMM's field, else against the learned one (learning it).
  void testReference(MagDisturbance& d, double dt_s);
  // A relative test's threshold: 4 times the learned floor, within 1-5 times the configured value.
  static double relativeThreshold(const NoiseFloor& floor, double configured);

  MagDisturbanceParams p_;
  LowPass<double> norm_lp_;
  LowPass<double> dip_lp_;
  LowPass<double> norm_deviation2_;  // for the noise floors: mean squares over about 1 s
  LowPass<double> dip_deviation2_;
  NoiseFloor norm_floor_;
  NoiseFloor dip_floor_;
  // The field's direction low-passed in a frame that turns with the gyro, and in the sensor's
  // axes; the angle between them is the sensor's turning against the field.
  GyroFrameLowPass direction_gyro_frame_;
  LowPass<Vec3> direction_sensor_axes_;
  Vec3 direction_turning_ = Vec3::Zero(), direction_still_ = Vec3::Zero();
  double turned_rad_ = 0.0;
  double norm_deviation_ = 0.0;
  double dip_deviation_ = 0.0;
  // The low-passes' strength and dip when the field was last clean for back_to_before_s,
  // how long it has been clean, and how long it has been back within the thresholds of them.
  bool has_before_ = false;
  double before_norm_uT_ = 0.0;
  double before_dip_rad_ = 0.0;
  double clean_s_ = 0.0;
  double back_s_ = 0.0;
  bool has_reference_ = false;
  double reference_norm_uT_ = 0.0;
  double reference_dip_rad_ = 0.0;
  // The learned field (no WMM reference): how long the field has been clean before the first,
  // and how long a different one has been homogeneous.
  bool has_learned_ = false;
  double learned_norm_uT_ = 0.0;
  double learned_dip_rad_ = 0.0;
  double learn_clean_s_ = 0.0;
  double different_s_ = 0.0;
};

}  // namespace headingd::core
