#pragma once
// Where the accelerometer saturates, learned from the data, and which axes of a sample read
// that limit.
//
// Why: phone accelerometers often run at ±2 g (the Nexus 5 and the iPhone 4S of the shared
// recordings). Running with the phone in the hand, a quarter of the samples of the axis along
// the arm read the limit while the body's specific force went 6-9 m/s² beyond it (measured
// on the iPhone 5 of the same recordings, which reads to ±8 g): the low-passed measurement,
// whose mean should be gravity, is then about 2 m/s² short along that axis. A clipped sample
// is not a bad sample (its other axes are exact); what the estimator needs to know is along
// which direction its low-pass is short (estimator.cpp: the gravity update trusts the
// measurement less along it).
//
// How: a saturated axis piles its readings up at one level and stays there for a while; an
// unsaturated signal does neither (the tail of a body's accelerations thins out towards its
// largest values, and a shaken sensor's sinusoid, whose values also crowd towards its peaks,
// passes through them). Per axis and sign, the readings beyond 1.5 g (below every
// accelerometer's full scale; gravity alone never gets there) are counted in bins 2 % wide
// that forget with a time constant of a minute, and so are those among them that have stayed
// within 0.5 % of one value for 20 ms ("flat"). Once a second the highest bin holding a few
// readings is the candidate limit, taken as one when the three bins up to it (6 %) hold at
// least 20 readings, more than three times as many as the three bins below them, and at least
// 15 % of them flat (measured: clipped running phones 29-32 %; a sinusoid of 1.5 g at 1 Hz,
// sampled at 100 Hz, 8 %; at 2.5 Hz none). From then on a reading within those 6 % of the
// limit (or beyond) is clipped on that axis.
#include <array>
#include <cstdint>

#include "headingd/core/quaternion.hpp"

namespace headingd::core {

class AccelClipDetector {
 public:
  AccelClipDetector();

  // Per sample: learns from the reading and returns, per axis, +1 or -1 where it reads the
  // learned positive or negative limit, else 0.
  Vec3 update(const Vec3& accel_m_s2, double dt_s);

  // The learned limit's lower edge (the smallest reading taken as clipped) of an axis and
  // sign (m/s², positive), +∞ while none is known.
  double clipFrom(int axis, bool negative) const { return clip_from_[slot(axis, negative)]; }

 private:
  static constexpr int kBins = 160;  // 2 % each from 1.5 g: to about 35 g
  static int slot(int axis, bool negative) { return 2 * axis + (negative ? 1 : 0); }
  void learn();

  std::array<std::array<double, kBins>, 6> counts_{};       // per axis and sign
  std::array<std::array<double, kBins>, 6> flat_counts_{};  // of them, the flat readings
  std::array<double, 6> clip_from_;
  Vec3 run_value_ = Vec3::Zero();      // per axis, the value the current flat run started at
  Vec3 run_s_ = Vec3::Constant(-1.0);  // and how long it has lasted (< 0: none, below 1.5 g)
  double since_learn_s_ = 0.0;
};

}  // namespace headingd::core
