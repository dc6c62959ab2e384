#pragma once
// How late a vector sensor is against the gyro, learned from the data, so that its samples
// can be turned to the attitude they belong to. Used for the magnetometer (phones: 20-40 ms
// late, and slower than the IMU) and for the accelerometer.
//
// A sensor Δ late reads v(t - Δ); in sensor axes a vector fixed in the earth (the field;
// gravity, for the specific force while the body's own acceleration averages out) turns as
// v̇ = -ω × v, and v(t - Δ) ≈ v(t) + Δ ω(t) × v(t). From a fresh sample at t1 the gyro
// turns it on to the next at t2 (Φ, the turn from t1's axes to t2's); what it differs by is
//     ρ = v_meas(t2) - Φ v_meas(t1) ≈ Δ (ω(t2) - Φ ω(t1)) × v(t2),
// a regression of ρ on x = (ω(t2) - Φ ω(t1)) × v(t2) (not zero where the turn rate changes:
// every stride, every swing). Δ̂ = Σ ρ·x / Σ |x|² over the clean samples, each sum forgetting with
// time_constant_s; σ(Δ̂) from the regression's residuals. What is not a turned earth vector
// (a residual hard iron, the body's acceleration) adds terms that the turn's changes average
// out. Only fresh samples count: a sensor slower than the IMU is repeated between its updates
// (held), and how long the current sample has been held (heldS) adds to its delay. An
// interval-mean sample of a sensor without delay gives Δ̂ ≈ dt/2, the estimator's default
// (vector_sample_lag_fraction).
//
// The regression assumes what made ρ is a delay. Whether the learned one is worth using is
// judged by what it claims to improve: the vector's angle to the down, which the tilt alone
// gives (the field's dip; for the specific force, 180°), should be steadier with it than
// without (scoreDownAngle).
#include <limits>

#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

struct VectorDelayParams {
  double max_delay_s = 0.1;            // |Δ̂| at most this; 0: not estimated, nor the held time
  double time_constant_s = 300.0;      // the sums forget with this time constant
  double apply_below_sigma_s = 0.005;  // Δ̂ counts once σ(Δ̂) is below this
  double min_span_s = 0.0;             // a regression's interval is at least this long (0: one fresh sample)
  // A reading equal to the last is the sensor's last update repeated (a magnetometer slower
  // than the IMU); false: every reading is fresh (an accelerometer at the IMU's rate, whose
  // readings at rest may repeat to the last bit).
  bool repeats_are_holds = true;
};

class VectorDelayEstimator {
 public:
  explicit VectorDelayEstimator(const VectorDelayParams& p)
      : p_(p), decay_(p.time_constant_s), chain_decay_(p.time_constant_s) {}

  // Per sample: the bias-corrected rate over the sample's interval of dt_s, and the vector
  // sample (nullptr: none). Only clean samples are learned from: when there is none or it is
  // not clean (a disturbed field, a clipped accelerometer) the chain of fresh samples starts
  // again.
  void update(const Vec3& gyro_rad_s, const Vec3* sample, bool clean, double dt_s);
  // A gap in the samples: the next fresh sample starts a new chain.
  void restartChain() { has_previous_ = false; }

  // The learned delay (s), clamped to ±max_delay_s, once its σ is below apply_below_sigma_s;
  // else 0.
  double candidateS() const { return candidate_s_; }

  // Whether the learned delay is worth using, judged where the model cannot fool itself: the
  // vector's angle to the down (which the tilt alone gives) should be steadier with it than
  // without. down_s: NED down in sensor axes; the sample turned to now by the default lag and
  // by the candidate delay. Both spreads forget with time_constant_s.
  void scoreDownAngle(const Vec3& down_s, const Vec3& turned_default, const Vec3& turned_delayed, bool clean,
                      double dt_s);
  bool useCandidate() const { return use_candidate_; }

  double estimateS() const { return estimate_s_; }
  double sigmaS() const { return sigma_s_; }
  // How long the current sample has been repeated unchanged (s): 0 for a fresh one.
  double heldS() const { return held_s_; }

 private:
  VectorDelayParams p_;
  bool has_previous_ = false;
  Vec3 start_rate_ = Vec3::Zero();  // the rate when the chain started, turned by the gyro since
  Vec3 predicted_ = Vec3::Zero();   // the last fresh sample turned by the gyro since
  double chain_s_ = 0.0;            // how long ago that sample was
  Vec3 last_seen_ = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());  // repeats_are_holds only
  double held_s_ = 0.0;
  double sum_xy_ = 0.0, sum_xx_ = 0.0, sum_yy_ = 0.0, count_ = 0.0;
  double estimate_s_ = 0.0, sigma_s_ = std::numeric_limits<double>::infinity();
  double candidate_s_ = 0.0;
  bool use_candidate_ = false;
  // The cosine of the angle to the down of the sample turned by the default lag [0] and by
  // the candidate [1]: weighted sums for their means and spreads.
  double angle_weight_ = 0.0;
  double cos_sum_[2] = {0.0, 0.0}, cos_sum_sq_[2] = {0.0, 0.0};
  // Two of the same time constant because each keeps the coefficient of one period: the
  // spreads' sums decay per sample (the IMU's period), the regression's per chain (one sample
  // of a slower sensor, or min_span_s and more); one cache for both would miss on every call.
  ExpDecay decay_;        // of the spreads' sums, per sample
  ExpDecay chain_decay_;  // of the regression's sums, per chain
};

}  // namespace headingd::core
