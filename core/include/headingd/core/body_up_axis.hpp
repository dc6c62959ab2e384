#pragma once
// The person's up axis (the direction of their head) in sensor axes, learned while they walk.
//
// Henriksson (2013) §3.3 takes the body's -z axis as the head: right for a sensor worn as
// documented (x forward, z down), wrong for any other mounting. A phone held screen-up has
// its z axis vertical while its owner stands, so the fixed -z axis says "lying down" (h of
// eq. 3.12 near -1) all the time. A person who walks is upright, so the mean direction of
// "up" seen in sensor axes over the walking is the person's up axis in sensor axes, whatever
// the mounting: a phone screen-up or in a pocket upside down, a sensor mounted flat.
//
// Once learned, only walking that agrees with it (the person upright by the axis, h above
// upright_above) refines it: crawling moves as walking does but is not upright, and must not
// tilt the axis. Walking that contradicts it (h below lying_below) for relearn_after_s of
// walking time means the sensor has been moved (a phone from the hand to a pocket): the axis
// is learned afresh. Nobody crawls that long; a phone is carried for minutes.
//
// Sensor axes are the estimator's body frame: q_nb maps them into NED.
#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

struct BodyUpAxisParams {
  Vec3 default_axis_s;     // until learned (kDocumentedHeadAxis for a sensor worn as documented)
  double time_constant_s;  // of the mean of the walking up direction (0: never learned)
  double min_walking_s;    // walking time before the learned axis replaces the default
  double relearn_after_s;  // walking time contradicting the axis before it is learned afresh
  double upright_above;    // h of eq. 3.12 above which walking agrees with the axis
  double lying_below;      // ... below which it contradicts it
};

class BodyUpAxis {
 public:
  explicit BodyUpAxis(const BodyUpAxisParams& p)
      : p_(p), axis_s_(p.default_axis_s.normalized()), alpha_(p.time_constant_s) {}

  // q_nb: the attitude after this sample; walking: the person walks or runs now.
  void update(const Quat& q_nb, bool walking, double dt_s);

  // Unit vector, sensor axes: the learned axis once enough walking has been seen, the
  // default before (and held while the person does not walk, and while it is learned afresh).
  const Vec3& axis() const { return axis_s_; }
  bool learned() const { return learned_; }  // axis() has been learned (not the default)
  // axis() is the person's: learned, or fixed by configuration (time constant 0: the default
  // axis is taken as the mounting). Before, the mounting is unknown.
  bool known() const { return learned_ || !(p_.time_constant_s > 0.0); }

 private:
  void learn(const Vec3& up_s, double dt_s);

  BodyUpAxisParams p_;
  Vec3 axis_s_;
  LowPassAlpha alpha_;
  Vec3 mean_up_s_ = Vec3::Zero();  // running mean of NED up seen in sensor axes while walking
  double walking_s_ = 0.0;         // walking time in that mean
  double contradicting_s_ = 0.0;   // walking time since the last walking that agreed with the axis
  bool learned_ = false;
  bool acquiring_ = true;  // learning from every walking sample: at the start, after a move
};

}  // namespace headingd::core
