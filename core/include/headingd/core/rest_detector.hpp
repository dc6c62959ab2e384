#pragma once
// Still stretches of the sensor and the gyro bias they show (gyro_bias_estimator.hpp).
//
// The sensor is still when nothing accelerates it and it turns slowly at most: a device on a
// table, a person standing, a hand holding it. Its rate is then judged in blocks of
// rest_min_duration_s. A block counts when, all through it:
//  - the gyro and the accelerometer are steady: the RMS deviations of ω and a from their
//    low-passed means (rest_filter_time_constant_s) stay below their bounds (the gyro's:
//    rest_gyro_threshold_rad_s or 2.5 times the gyro's own learned noise floor, whichever is
//    larger, up to rest_gyro_max_threshold_rad_s; the accelerometer's is absolute, since it
//    is what tells a person standing from one moving). A variance test, so that one noisy
//    sample does not end a rest. Until the floor is known (its first 4 filter time constants)
//    the gyro's test is provisional: the stretch's largest RMS is kept and held against the
//    bound once the floor is known, and no block ends before. A fixed bound there missed the
//    1-5 s opening rests of noisy phone and consumer gyros (0.01-0.04 rad/s per sample):
//    their bias was then never learned (issue 28). The bound is then also 2.5 times the
//    stretch's own quietest RMS: the floor's first value is the RMS of the moment it becomes
//    known, a motion's when the rest was shorter than the warm-up, and a block with a motion's
//    start in it passed (30 mrad/s of bias learned wrong, simulated phone-running-circles).
//    A block that fails it is cut back to where its RMS was still quiet, and counts if that
//    part is at least half a block;
//  - the mean rate is no more than a plausible bias plus a slow turn;
// and the world's vectors say how far it turned: from the block's start to its end the
// low-passed directions of gravity (accelerometer) and, when the field is usable and
// undisturbed all through, of the field (magnetometer) move as the sensor turns, Δu = u × θ.
// Gravity sees the part of θ about horizontal axes, the field the part about the vertical.
// Hypotheses are weighed by their Bayes factors: each part of the turn, about the horizontal
// axes and about the vertical, lay still (0) or turned a little (N(0, σ_p²), σ_p half of
// rest_max_turn_rate_rad_s times the block's length), each with equal prior odds; apart, so
// that a standing body's sway about horizontal axes, which gravity sees clearly, does not make
// the field's noisier view of the vertical count in full.
// The block's bias is (∫ω̄ dt - θ̂) / T with θ̂ the mixture's turn: a turn the vectors clearly
// saw is taken off, mere noise is not (so a sensor that lies still gets the gyro's own
// precision, not the field's noise). A block counts when θ̂ is within the turn limit and the
// two vectors fit one rotation (else something accelerated the sensor or disturbed the field).
//
// Why: a slow steady turn or a hand's slow drift (1-3 deg/s) keeps the gyro and the
// accelerometer steady; taking its mean rate as bias (what a gyro-only rest test does) leaves
// a bias error of that rate, which the tilt filter turns into degrees of tilt.
// Gravity and the field measure the turn itself. Nothing here compares with the current bias
// estimate: a test against the estimate (|ω̄ - b̂| small) locks a wrong estimate in, since
// the true rest then fails it. Without a usable field a turn about the vertical is not seen
// and is taken as none: the block counts that part of its rate as bias (a person standing
// sways about horizontal axes; a slow steady turn about the vertical is the limitation).
// A block grows while the rest goes on: judged again every rest_min_duration_s from its own
// start, it replaces its last version, up to bias_time_constant_s (the estimate's memory at
// rest; then it stands and the next one begins). Why: the field's view of a turn about the
// vertical is its horizontal part's noise over a turn of a few degrees, which within one
// block of 1.5 s hides a hand's slow drift (1-2.5 deg/s), so each block took most of it as
// bias, and consecutive blocks, counted as independent, made a confident estimate of it (a
// phone held at 70° pitch, simulated hand-held, seeds 5 and 7: 15 mrad/s wrong at 6 sigma).
// Over a grown block the turn grows with its length and the noise does not. A grown block
// that lost the field, or fails its tests, stands as last counted, and a new one begins.
// The first moments of a motion pass every test (a slow start; a person setting off, whose
// acceleration tilts the apparent gravity, which a block takes for a turn: 15 mrad/s of bias
// learned wrong, simulated phone-running-circles consumer seed 6) and are found a few tenths of
// a second later. So what lay within a confirmation window (one low-pass time constant, at
// most half a block) before a motion was found does not count: a block in progress then counts
// up to that moment if that part is at least half a time constant long and its gyro stayed
// quiet (an opening rest of 1-1.5 s gives no whole block), and a block that ended less than a
// window before is cut back to it (withdrawn if that part is not still); the bias estimate is
// then redone from the cut block. After a motion the first block starts only once the
// low-passes have settled from it (3 of their time constants of steadiness; at start-up they
// begin as running means and need one).
#include <limits>
#include <vector>

#include "headingd/core/estimator_params.hpp"
#include "headingd/core/low_pass.hpp"
#include "headingd/core/noise_floor.hpp"
#include "headingd/core/quaternion.hpp"

namespace headingd::core {

// A still block that ended with this sample: the bias it shows and its length.
struct RestBlock {
  Vec3 bias_rad_s = Vec3::Zero();  // mean rate less the turn gravity and the field saw
  double duration_s = 0.0;
  // Covariance of bias_rad_s from the block's own noise: the gyro's white noise over the
  // block and the uncertainty of the measured turn.
  Mat3 covariance = Mat3::Zero();
};

class RestDetector {
 public:
  explicit RestDetector(const EstimatorParams& p);

  // What a sample tells about still blocks.
  enum class News {
    kNone,
    kNewBlock,            // a still block ended with this sample: block() holds it
    kLastBlockRevised,    // the last block grew (the rest went on): block() holds it, which
                          // replaces it; or a motion was found just after the last block:
                          // block() holds its part before the motion (or, for a grown block,
                          // its version before it last grew), which replaces it
    kLastBlockWithdrawn,  // ... and too little of it lay before the motion: it does not count
  };
  // mag_uT: the field sample, or nullptr when there is none or it is disturbed.
  News update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, const Vec3* mag_uT, double dt_s);
  // At rest: the last block was still and the sensor has stayed steady since.
  bool atRest() const { return at_rest_; }
  const RestBlock& block() const { return block_; }

 private:
  // One vector's low-passed mean and the mean squared deviation of the samples from it. Both low-passes begin as
  // running means (weight dt/t until t reaches the time constant), so the first samples do not weigh more than later
  // ones.
  struct SteadyVector {
    explicit SteadyVector(double time_constant_s) : alpha(time_constant_s) {}
    double update(const Vec3& v, double dt_s);  // returns the RMS deviation
    Vec3 direction() const { return mean.normalized(); }
    // Standard deviation of the mean's direction (rad) from the sensor's noise floor: white
    // noise σ through a first-order low-pass has σ √(dt / 2τ), dt the sensor's own sample
    // period (a sample repeated until the next one, a phone's magnetometer at 25-50 Hz read
    // at 100 Hz, is one sample, not several: at the IMU's dt the field's direction looked 1.4-2
    // times steadier than it was, and its noise passed for a turn about the vertical).
    // rms_at_end: the deviation where the block judged ends, while the floor is not known.
    double directionSigma(const NoiseFloor& floor, double rms_at_end, double dt_s, double time_constant_s) const;
    LowPassAlpha alpha;
    double elapsed_s = 0.0;
    Vec3 mean = Vec3::Zero();
    double deviation2 = 0.0;
    // The sensor's own sample period: the time between changed samples, averaged.
    Vec3 last = Vec3::Zero();
    double since_change_s = 0.0;
    double sample_period_s = 0.0;  // 0 until a second change
  };

  // A block's course, sample by sample: where it stands after time_s, what a cut judges.
  struct BlockPoint {
    double time_s;
    Vec3 rotation;  // ∫ ω̄ dt since the block began
    Vec3 accel_direction;
    Vec3 mag_direction;  // zero without the field
    double gyro_rms;     // RMS deviations of the three vectors there
    double accel_rms;
    double mag_rms;  // zero without the field
  };
  // A block: the directions its turn is measured from and its course (the first
  // kCoursePoints samples: at 1 kHz and below, all of a 2 s block; at 200 Hz, of a 10 s grown one).
  struct Block {
    Vec3 accel_start = Vec3::Zero();
    Vec3 mag_start = Vec3::Zero();
    bool with_mag = false;  // the field was usable when the block began and since
    std::vector<BlockPoint> course;
  };

  void startBlock(bool with_mag);
  // The block's turn from gravity (and the field), from their directions at its start to
  // `end`'s, and its covariance, or false if they do not fit one rotation.
  bool measuredTurn(double dt_s, const Block& block, const BlockPoint& end, Vec3* turn_rad, Mat3* covariance) const;
  // The still block's bias from its integral and measured turn up to `end`, or false when the
  // turn is not one rotation or too large. at_rest_ follows.
  bool judgeBlock(double dt_s, const Block& block, const BlockPoint& end);
  // Of the provisional stretch's block (the gyro floor unknown when it began), the part before
  // its RMS rose above `bound`: its bias, if that part is long enough and still.
  bool judgeQuietPart(double dt_s, double bound);
  // Of `block`, the part that ended at end_s (block time; when a motion was found: a
  // confirmation window before): its bias, if that part is at least min_s long, its gyro's
  // RMS stayed below gyro_bound all through, and it is still.
  bool judgePart(double dt_s, const Block& block, double end_s, double min_s, double gyro_bound);
  // How long the sensor must stay steady after a still block for the block to stand.
  double confirmWindowS() const;
  // The block in progress at one of its judgements (every rest_min_duration_s): counted for
  // the first time, grown (it replaces its last version), or it stands as last counted.
  News judgeGrowingBlock(double dt_s, const BlockPoint& now, bool has_mag);
  // The block in progress has counted with the field and lost it since.
  bool lostField() const;

  EstimatorParams p_;  // a copy: the owner may be copied or moved (gyro_bias_estimator.hpp)
  SteadyVector gyro_;
  SteadyVector accel_;
  SteadyVector mag_;
  NoiseFloor gyro_floor_;
  NoiseFloor accel_floor_;  // kept through the field's absences (mag_ restarts)
  NoiseFloor mag_floor_;
  bool at_rest_ = false;
  double steady_s_ = 0.0;              // how long the steady tests have held
  double provisional_gyro_rms_ = 0.0;  // largest gyro RMS of the stretch before the floor was known
  double provisional_min_rms_ = std::numeric_limits<double>::infinity();  // and its smallest, once settled
  // Time constants of steadiness before a block may start: one at start-up (the running means
  // have then seen a time constant's samples), three after a motion (they still hold it).
  double settle_time_constants_ = 1.0;
  bool in_block_ = false;
  double field_gap_s_ = 0.0;         // how long the field has been missing, at a stretch
  double block_field_gaps_s_ = 0.0;  // and in all, this block
  double block_time_s_ = 0.0;
  Vec3 block_rotation_ = Vec3::Zero();  // ∫ ω̄ dt over the block
  Block current_;
  double next_judgement_s_ = 0.0;   // block time of the current block's next judgement
  int block_counted_ = 0;           // how often the current block has counted (0: not yet)
  bool counted_with_mag_ = false;   // the field saw its last counted version
  RestBlock before_growth_;         // the block as it counted before it last grew
  bool pending_is_growth_ = false;  // the pending block is a grown one (its fallback: before_growth_)
  RestBlock block_;
  // The last still block while the steadiness after it is not yet a confirmation window long.
  bool has_pending_ = false;
  Block pending_;
  double pending_duration_s_ = 0.0;
  double pending_age_s_ = 0.0;
};

}  // namespace headingd::core
