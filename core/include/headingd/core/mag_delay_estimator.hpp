#pragma once
// How late the magnetometer is against the gyro, learned from the data (phones: 20-40 ms,
// their magnetometer also slower than the IMU), so that the field can be turned to the
// attitude it belongs to.
//
// A magnetometer Δ late reads m(t - Δ) (in sensor axes a constant field turns as
// ṁ = -ω × m). From a fresh field sample at t1 the gyro turns it on to the next at t2; the
// late field turned with ω(t - Δ) meanwhile, so what it differs by is
//     ρ = m_meas(t2) - m_pred(t2) ≈ Δ ∫ ω̇ × m dt   (t1 to t2),
// a regression of ρ on x = ∫ ω̇ × m dt (not zero where the turn rate changes: every stride,
// every swing). Δ̂ = Σ ρ·x / Σ |x|² over the clean field's samples, each sum forgetting with
// time_constant_s; σ(Δ̂) from the regression's residuals. A residual hard iron adds a term
// that the turn's changes average out. Only fresh samples count: a magnetometer slower than
// the IMU is repeated between its updates (held), and how long the current sample has been
// held (heldS) adds to its delay. An interval-mean field sample of a sensor without delay
// gives Δ̂ ≈ dt/2, the estimator's default (vector_sample_lag_fraction).
//
// The regression assumes what made ρ is a delay. Whether the learned one is worth using is
// judged by what it claims to improve: the dip of the field, which the tilt alone gives, is
// steadier with it than without (scoreDip).
#include <limits>

#include "headingd/core/low_pass.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

struct MagDelayParams {
  double max_delay_s = 0.1;        // |Δ̂| at most this; 0: not estimated, nor the held time
  double time_constant_s = 300.0;  // the sums forget with this time constant
  double apply_below_sigma_s = 0.005;  // Δ̂ counts once σ(Δ̂) is below this
};

class MagDelayEstimator {
 public:
  explicit MagDelayEstimator(const MagDelayParams& p) : p_(p), decay_(p.time_constant_s) {}

  // Per sample: the bias-corrected rate over the sample's interval of dt_s, and the field
  // sample (nullptr: none). Only a clean field is learned from: when there is none or it is
  // disturbed the chain of fresh samples starts again.
  void update(const Vec3& gyro_rad_s, const Vec3* mag_uT, bool clean, double dt_s);
  // A gap in the samples: the next fresh field sample starts a new chain.
  void restartChain() { has_previous_ = false; }

  // The learned delay (s), clamped to ±max_delay_s, once its σ is below apply_below_sigma_s;
  // else 0.
  double candidateS() const { return candidate_s_; }

  // Whether the learned delay is worth using, judged where the model cannot fool itself: the
  // dip of the field (its angle below the horizontal, which the tilt alone gives) should be
  // steadier with it than without. down_s: NED down in sensor axes; the field turned to now
  // by the default lag and by the candidate delay. Both spreads forget with time_constant_s.
  void scoreDip(const Vec3& down_s, const Vec3& mag_default, const Vec3& mag_delayed, bool clean, double dt_s);
  bool useCandidate() const { return use_candidate_; }

  double estimateS() const { return estimate_s_; }
  double sigmaS() const { return sigma_s_; }
  // How long the current field sample has been repeated unchanged (s): 0 for a fresh one.
  double heldS() const { return held_s_; }

 private:
  MagDelayParams p_;
  bool has_previous_ = false;
  Vec3 previous_gyro_ = Vec3::Zero();
  Vec3 regressor_ = Vec3::Zero();       // ∫ ω̇ × m dt since the last fresh sample
  Vec3 predicted_ = Vec3::Zero();       // the last fresh sample turned by the gyro since
  Vec3 last_seen_ = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  double held_s_ = 0.0;
  double sum_xy_ = 0.0, sum_xx_ = 0.0, sum_yy_ = 0.0, count_ = 0.0;
  double estimate_s_ = 0.0, sigma_s_ = std::numeric_limits<double>::infinity();
  double candidate_s_ = 0.0;
  bool use_candidate_ = false;
  // sin(dip) of the field turned by the default lag [0] and by the candidate [1]: weighted
  // sums for their means and spreads.
  double dip_weight_ = 0.0;
  double dip_sum_[2] = {0.0, 0.0}, dip_sum_sq_[2] = {0.0, 0.0};
  ExpDecay decay_;  // of every sum above, per sample
};

}  // namespace headingd::core
