#include "headingd/core/rest_detector.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace headingd::core {

namespace {

// Time constants of the low-passes that a steady stretch must last before a block starts.
constexpr double kSettleTimeConstants = 3.0;
// The field may be missing (flagged as disturbed) for this long at a stretch, and for this
// share of a block in all, and still count in it: single false alarms of a noisy
// magnetometer's disturbance tests must not take the field's view of the vertical away.
constexpr double kMaxFieldGapS = 0.1;
constexpr double kMaxFieldGapShare = 0.2;
// A provisional block cut back to its quiet part counts if that part is at least this share of
// rest_min_duration_s.
constexpr double kMinQuietShare = 0.5;
// A block that a motion ends counts up to a confirmation window before the motion was found if
// that part is at least this many of the low-pass's time constants long (with the default
// 0.5 s: 0.25 s). Shorter than a block: the opening rests of 1-1.5 s (phone-calling,
// -pocket, -swinging) never gave a whole one, and their bias was then learned in motion only,
// slowly; the part's covariance says how little a short one knows.
constexpr double kMinPartTimeConstants = 0.5;
// The stretch's quietest RMS is taken from this many of the low-pass's time constants on: the
// running means' first moments understate it (a hand's tremor at 1 τ: 0.017 against 0.042 rad/s
// later, simulated hand-held, seed 2).
constexpr double kQuietFromTimeConstants = 2.0;
// A still block counts once the sensor has stayed steady for this many of the low-pass's time
// constants after it (at most half a block; rest_detector.hpp says why).
constexpr double kConfirmTimeConstants = 1.0;
// Weight of each new interval in a sensor's averaged sample period (about the last ten).
constexpr double kSamplePeriodWeight = 0.1;
// A block's course is kept for this many samples: the floor's 2 s warm-up at 1 kHz, a grown
// block's 10 s (bias_time_constant_s) at 200 Hz (at higher rates its first part only).
constexpr std::size_t kCoursePoints = 2048;

}  // namespace

RestDetector::RestDetector(const EstimatorParams& p)
    : p_(p),
      gyro_(p.rest_filter_time_constant_s),
      accel_(p.rest_filter_time_constant_s),
      mag_(p.rest_filter_time_constant_s),
      gyro_floor_(4.0 * p.rest_filter_time_constant_s),
      accel_floor_(4.0 * p.rest_filter_time_constant_s),
      mag_floor_(4.0 * p.rest_filter_time_constant_s) {
  // Once, here: the estimator's loop does not allocate.
  current_.course.reserve(kCoursePoints);
  pending_.course.reserve(kCoursePoints);
}

double RestDetector::SteadyVector::update(const Vec3& v, double dt_s) {
  elapsed_s += dt_s;
  const double low_pass_weight = 1.0 - alpha(dt_s);  // eq. 2.13
  const double weight = startedLowPassWeight(elapsed_s, dt_s, low_pass_weight);
  mean += weight * (v - mean);
  deviation2 += weight * ((v - mean).squaredNorm() - deviation2);
  since_change_s += dt_s;
  if (v != last) {
    if (elapsed_s > since_change_s) {  // not the first sample: an interval between changes
      sample_period_s = sample_period_s > 0.0
                            ? sample_period_s + kSamplePeriodWeight * (since_change_s - sample_period_s)
                            : since_change_s;
    }
    last = v;
    since_change_s = 0.0;
  }
  return std::sqrt(deviation2);
}

double RestDetector::SteadyVector::directionSigma(const NoiseFloor& floor, double rms_at_end, double dt_s,
                                                  double time_constant_s) const {
  const double norm = mean.norm();
  if (norm <= 0.0) return 1.0;
  // The sensor's own noise: the quietest RMS deviation of the last minute (a turn or a
  // tremor raises the deviation, and is what the block measures, not noise); the current
  // deviation until the floor is known. A floor of 1e-5 rad keeps the weights finite for a
  // noiseless (simulated) sensor.
  const double known_floor = floor.value();
  const double rms = std::isfinite(known_floor) ? known_floor : rms_at_end;
  const double period_s = std::max(dt_s, sample_period_s);
  return std::max(1e-5, rms * std::sqrt(period_s / (2.0 * time_constant_s)) / norm);
}

bool RestDetector::measuredTurn(double dt_s, const Block& block, const BlockPoint& end, Vec3* turn_rad,
                                Mat3* covariance) const {
  // A world-fixed unit vector seen from a sensor that turns by θ (sensor axes) moves by
  // Δu = u₀ × θ = [u₀]× θ. Gravity and the field each measure θ so, weighted by their
  // direction noise (the start and the end mean each contribute): in information form
  // I_m = Σ [u]×ᵀ[u]× / σ² = Σ (I - u uᵀ) / σ² and b_m = Σ [u]×ᵀ Δu / σ².
  // Hypotheses: the block lay still (θ = 0), or it turned, θ ~ N(0, σ_p² I) with σ_p half
  // the largest turn a block may make, about the horizontal axes, the vertical, or both
  // (below). Their Bayes factors weigh them, and θ is their mixture: taken off in full when
  // the vectors clearly saw a turn, not at all when they saw only noise (then the gyro's mean
  // alone is the bias, as precise as the gyro is), in between with the covariance of the
  // mixture. Without a usable field the part about gravity is not seen at all: it is taken as
  // still (a person standing sways about horizontal axes, and indoors, where the field is
  // often disturbed, that is how the vertical bias is learned; a slow steady turn about the
  // vertical then counts as bias).
  const double tau = p_.rest_filter_time_constant_s;
  const double prior_sigma = 0.5 * p_.rest_max_turn_rate_rad_s * end.time_s;
  const double prior_variance = std::max(prior_sigma * prior_sigma, 1e-12);
  Mat3 measured_information = Mat3::Zero();
  Vec3 projected = Vec3::Zero();
  struct Seen {
    Vec3 start, end;
    double variance;
  };
  Seen seen[2];
  int count = 0;
  const double accel_sigma = accel_.directionSigma(accel_floor_, end.accel_rms, dt_s, tau);
  seen[count++] = {block.accel_start, end.accel_direction, 2.0 * accel_sigma * accel_sigma};
  if (block.with_mag) {
    const double mag_sigma = mag_.directionSigma(mag_floor_, end.mag_rms, dt_s, tau);
    seen[count++] = {block.mag_start, end.mag_direction, 2.0 * mag_sigma * mag_sigma};
  }
  for (int i = 0; i < count; ++i) {
    const Vec3& u = seen[i].start;
    measured_information += (Mat3::Identity() - u * u.transpose()) / seen[i].variance;
    projected += crossMatrix(u).transpose() * (seen[i].end - u) / seen[i].variance;
  }
  // Each part, about the horizontal axes and about the vertical, lay still or turned:
  // θ ~ N(0, P₀) with P₀ = σ_p² times the projector on the parts that turned. Against the
  // still block, ln(p(data | P₀) / p(data | still)) = -½ ln det(I + P₀ I_m) + ½ b_mᵀ A⁻¹ P₀ b_m,
  // A = I + P₀ I_m, and the posterior is N(A⁻¹ P₀ b_m, A⁻¹ P₀). Each part's two hypotheses have
  // equal prior odds. Separately, because a person standing sways about horizontal axes,
  // which gravity sees clearly: weighed as one, that sway made the turn about the vertical,
  // which only the field's noisier horizontal part sees, count in full, noise and all (a body
  // standing still about the vertical, simulated crawl, consumer, seed 14: 12 mrad/s).
  const Vec3& g = block.accel_start;
  const Mat3 about_vertical = g * g.transpose();
  const Mat3 about_horizontal = Mat3::Identity() - about_vertical;
  struct Hypothesis {
    Mat3 prior_covariance;
    double log_evidence = 0.0;  // against the still block
    Vec3 mean = Vec3::Zero();
    Mat3 covariance = Mat3::Zero();
  };
  Hypothesis hypotheses[4] = {{Mat3::Zero()},
                              {prior_variance * about_horizontal},
                              {prior_variance * about_vertical},
                              {prior_variance * Mat3::Identity()}};
  // Without a usable field the part about the vertical is not seen: it is taken as still.
  const int hypothesis_count = block.with_mag ? 4 : 2;
  double max_log_evidence = 0.0;
  for (int h = 1; h < hypothesis_count; ++h) {
    Hypothesis& hyp = hypotheses[h];
    const auto A = (Mat3::Identity() + hyp.prior_covariance * measured_information).partialPivLu();
    hyp.mean = A.solve(hyp.prior_covariance * projected);
    hyp.covariance = A.solve(hyp.prior_covariance);
    hyp.covariance = 0.5 * (hyp.covariance + hyp.covariance.transpose());
    hyp.log_evidence = -0.5 * std::log(A.determinant()) + 0.5 * projected.dot(hyp.mean);
    max_log_evidence = std::max(max_log_evidence, hyp.log_evidence);
  }
  double total_weight = 0.0;
  for (int h = 0; h < hypothesis_count; ++h) total_weight += std::exp(hypotheses[h].log_evidence - max_log_evidence);
  Vec3 mixture_mean = Vec3::Zero();
  Mat3 second_moment = Mat3::Zero();
  for (int h = 1; h < hypothesis_count; ++h) {
    const Hypothesis& hyp = hypotheses[h];
    const double weight = std::exp(hyp.log_evidence - max_log_evidence) / total_weight;
    mixture_mean += weight * hyp.mean;
    second_moment += weight * (hyp.covariance + hyp.mean * hyp.mean.transpose());
  }
  *turn_rad = mixture_mean;
  *covariance = second_moment - mixture_mean * mixture_mean.transpose();
  // Whether the vectors fit one rotation is asked of the hypothesis that every part turned.
  const Vec3& turned = hypotheses[hypothesis_count - 1].mean;
  // What one rotation cannot explain (a linear acceleration, a field that changed) must be
  // within 4σ of each vector's noise, plus 0.1 deg for the small-angle model.
  for (int i = 0; i < count; ++i) {
    const Vec3 residual = seen[i].end - seen[i].start - crossMatrix(seen[i].start) * turned;
    if (residual.norm() > 4.0 * std::sqrt(seen[i].variance) + 0.0017) return false;
  }
  return true;
}

bool RestDetector::judgeBlock(double dt_s, const Block& block, const BlockPoint& end) {
  Vec3 turn;
  Mat3 turn_covariance;
  const double block_s = end.time_s;
  const bool still =
      measuredTurn(dt_s, block, end, &turn, &turn_covariance) && turn.norm() <= p_.rest_max_turn_rate_rad_s * block_s;
  at_rest_ = still;
  if (still) {
    // ∫ω̄ dt over T carries the gyro's white noise as ∫ω dt does: σ² dt T, σ² the samples'
    // mean squared deviation.
    // (The deviation where the part judged ends: a motion found later has raised it since.)
    Mat3 covariance = (end.gyro_rms * end.gyro_rms * dt_s / block_s) * Mat3::Identity();
    covariance += turn_covariance / (block_s * block_s);
    block_ = {(end.rotation - turn) / block_s, block_s, covariance};
  }
  return still;
}

bool RestDetector::judgeQuietPart(double dt_s, double bound) {
  // The last point before the RMS first rose above the bound.
  const auto& course = current_.course;
  std::size_t quiet = 0;
  while (quiet < course.size() && course[quiet].gyro_rms < bound) ++quiet;
  if (quiet == 0) return false;
  const BlockPoint& end = course[quiet - 1];
  if (end.time_s < kMinQuietShare * p_.rest_min_duration_s) return false;
  return judgeBlock(dt_s, current_, end);
}

bool RestDetector::judgePart(double dt_s, const Block& block, double end_s, double min_s, double gyro_bound) {
  const auto& course = block.course;
  const auto after = std::upper_bound(course.begin(), course.end(), end_s,
                                      [](double t, const BlockPoint& point) { return t < point.time_s; });
  if (after == course.begin()) return false;
  const BlockPoint& end = *std::prev(after);
  if (end.time_s < min_s) return false;
  if (std::any_of(course.begin(), after,
                  [gyro_bound](const BlockPoint& point) { return point.gyro_rms >= gyro_bound; })) {
    return false;
  }
  return judgeBlock(dt_s, block, end);
}

bool RestDetector::lostField() const {
  // A grown block that lost the field would take its turn about the vertical as none: the
  // version the field saw stands.
  return block_counted_ > 0 && counted_with_mag_ && !current_.with_mag;
}

double RestDetector::confirmWindowS() const {
  return std::min(kConfirmTimeConstants * p_.rest_filter_time_constant_s, 0.5 * p_.rest_min_duration_s);
}

void RestDetector::startBlock(bool with_mag) {
  in_block_ = true;
  current_.course.clear();
  current_.accel_start = accel_.direction();
  current_.with_mag = with_mag;
  current_.mag_start = with_mag ? mag_.direction() : Vec3::Zero();
  block_time_s_ = 0.0;
  block_rotation_.setZero();
  block_field_gaps_s_ = 0.0;
  block_counted_ = 0;
  next_judgement_s_ = p_.rest_min_duration_s;
}

RestDetector::News RestDetector::update(const Vec3& gyro_rad_s, const Vec3& accel_m_s2, const Vec3* mag_uT,
                                        double dt_s) {
  const double gyro_rms = gyro_.update(gyro_rad_s, dt_s);
  const double accel_rms = accel_.update(accel_m_s2, dt_s);
  accel_floor_.update(accel_rms, dt_s);
  if (mag_uT != nullptr) {
    const double mag_rms = mag_.update(*mag_uT, dt_s);
    // A mean that starts afresh has no deviation yet: the floor learns from settled ones only.
    if (mag_.elapsed_s >= kSettleTimeConstants * p_.rest_filter_time_constant_s) mag_floor_.update(mag_rms, dt_s);
    field_gap_s_ = 0.0;
  } else {
    // Single samples flagged as disturbed (a noisy magnetometer's false alarms) are skipped.
    // A longer absence: the field's mean starts afresh when it comes back (an old mean
    // would look like a turn), and the current block goes on without it.
    field_gap_s_ += dt_s;
    block_field_gaps_s_ += dt_s;
    if (field_gap_s_ > kMaxFieldGapS || block_field_gaps_s_ > kMaxFieldGapShare * p_.rest_min_duration_s) {
      mag_ = SteadyVector(p_.rest_filter_time_constant_s);
      current_.with_mag = false;
    }
  }
  gyro_floor_.update(gyro_rms, dt_s);
  // Until the gyro's noise floor is known (its warm-up), a noisy gyro's rest cannot be told
  // from a motion by its own RMS: a fixed bound would reject a consumer gyro's rest (0.01-0.03
  // rad/s per sample) and a short opening rest would be over before the floor is. So the gyro
  // test is provisional then: the stretch goes on (the accelerometer's absolute test and the
  // mean rate still apply) with its largest RMS kept, and once the floor is known that RMS is
  // held against the bound; no block ends before.
  const bool floor_known = std::isfinite(gyro_floor_.value());
  const double gyro_bound = gyro_floor_.threshold(2.5, p_.rest_gyro_threshold_rad_s, p_.rest_gyro_max_threshold_rad_s);
  if (!floor_known) {
    provisional_gyro_rms_ = std::max(provisional_gyro_rms_, gyro_rms);
    if (gyro_.elapsed_s >= kQuietFromTimeConstants * p_.rest_filter_time_constant_s) {
      provisional_min_rms_ = std::min(provisional_min_rms_, gyro_rms);
    }
  }
  // The floor's first value is the RMS of the moment it becomes known: if the stretch has
  // turned into a motion by then (an opening rest shorter than the floor's warm-up), that value
  // is the motion's. The stretch's own quietest RMS bounds it too.
  const double provisional_bound =
      std::min(gyro_bound,
               std::clamp(2.5 * provisional_min_rms_, p_.rest_gyro_threshold_rad_s, p_.rest_gyro_max_threshold_rad_s));
  const bool provisional_failed = floor_known && provisional_gyro_rms_ >= provisional_bound;
  const bool gyro_steady =
      floor_known ? gyro_rms < gyro_bound && !provisional_failed : gyro_rms < p_.rest_gyro_max_threshold_rad_s;
  const bool steady = gyro_steady && accel_rms < p_.rest_accel_threshold_m_s2 &&
                      gyro_.mean.norm() <= p_.bias_max_rad_s + p_.rest_max_turn_rate_rad_s;
  if (floor_known) {
    provisional_gyro_rms_ = 0.0;  // held against the bound once, above
    provisional_min_rms_ = std::numeric_limits<double>::infinity();
  }
  // A failed provisional block's quiet start may still be a rest: judged alone (the stretch
  // ends here all the same).
  const bool quiet_part_still = provisional_failed && in_block_ && judgeQuietPart(dt_s, provisional_bound);
  if (!steady) {
    // The last block, if it ended less than a confirmation window ago, counts only up to a
    // window before this moment. (Not with a quiet part: no block ends before the floor is
    // known, and the provisional test fails only when it becomes known.)
    News news = quiet_part_still ? News::kNewBlock : News::kNone;
    if (has_pending_) {
      // (It passed its tests whole: its part needs no gyro bound, and is at least half a block.)
      const bool still = judgePart(dt_s, pending_, pending_duration_s_ + pending_age_s_ - confirmWindowS(),
                                   kMinQuietShare * p_.rest_min_duration_s, std::numeric_limits<double>::infinity());
      // A grown block whose part fails falls back to what it was before it last grew (a block
      // or more earlier, so that version's own window has passed).
      if (!still && pending_is_growth_) block_ = before_growth_;
      news = still || pending_is_growth_ ? News::kLastBlockRevised : News::kLastBlockWithdrawn;
    }
    // A block in progress that has not counted yet counts up to a window before this moment,
    // if that part is long enough and its gyro stayed quiet (the opening rests of 1-1.5 s,
    // shorter than a block): below the bound, or while the floor is not known yet, below 2.5
    // times the quietest RMS of the stretch and of the block (the bound's minimum then is a
    // fixed one, which a phone's gyro at 100 Hz does not meet: 0.007 rad/s per sample and
    // axis). A grown block stands as last counted: counting its growth since, up to the
    // window, took in the starts of motions on the shared phone recordings with magnets
    // (Nexus 5, fitted: 4.40 -> 5.97 deg).
    if (news == News::kNone && !has_pending_ && in_block_ && block_counted_ == 0) {
      double part_bound = gyro_bound;
      if (!floor_known) {
        double quietest = provisional_min_rms_;
        for (const BlockPoint& point : current_.course) quietest = std::min(quietest, point.gyro_rms);
        part_bound = std::clamp(2.5 * quietest, p_.rest_gyro_threshold_rad_s, p_.rest_gyro_max_threshold_rad_s);
      }
      const double min_s = kMinPartTimeConstants * p_.rest_filter_time_constant_s;
      if (judgePart(dt_s, current_, block_time_s_ - confirmWindowS(), min_s, part_bound)) news = News::kNewBlock;
    }
    has_pending_ = false;
    steady_s_ = 0.0;
    // After a motion the low-passed means still hold it for a few time constants.
    settle_time_constants_ = kSettleTimeConstants;
    in_block_ = false;
    at_rest_ = false;
    return news;
  }
  steady_s_ += dt_s;
  if (has_pending_) {
    pending_age_s_ += dt_s;
    if (pending_age_s_ >= confirmWindowS()) has_pending_ = false;  // it stands
  }
  if (steady_s_ < settle_time_constants_ * p_.rest_filter_time_constant_s) return News::kNone;
  if (!in_block_) startBlock(mag_uT != nullptr);
  block_time_s_ += dt_s;
  // The low-passed rate: its integral over the block is the turn the low-passed directions
  // below see (the filter is linear), so the two compare over the same stretch of time.
  block_rotation_ += gyro_.mean * dt_s;
  const BlockPoint now{block_time_s_,
                       block_rotation_,
                       accel_.direction(),
                       current_.with_mag ? mag_.direction() : Vec3::Zero(),
                       gyro_rms,
                       accel_rms,
                       current_.with_mag ? std::sqrt(mag_.deviation2) : 0.0};
  if (current_.course.size() < kCoursePoints) current_.course.push_back(now);
  if (block_time_s_ < next_judgement_s_ || !floor_known) return News::kNone;
  return judgeGrowingBlock(dt_s, now, mag_uT != nullptr);
}

RestDetector::News RestDetector::judgeGrowingBlock(double dt_s, const BlockPoint& now, bool has_mag) {
  next_judgement_s_ = block_time_s_ + p_.rest_min_duration_s;
  const bool grown = block_counted_ > 0;
  if (lostField()) {
    startBlock(has_mag);
    return News::kNone;
  }
  const RestBlock counted = block_;
  if (!judgeBlock(dt_s, current_, now)) {
    startBlock(has_mag);  // a grown block stands as last counted; the next one begins here
    return News::kNone;
  }
  ++block_counted_;
  counted_with_mag_ = current_.with_mag;
  has_pending_ = confirmWindowS() > 0.0;
  pending_is_growth_ = grown;
  pending_age_s_ = 0.0;
  if (grown) before_growth_ = counted;
  if (has_pending_) {
    // The course as it stands, for a cut (both keep their reserved capacity: no allocation).
    // Above 200 Hz a grown block outlasts its course, and a cut then ends at the course's end.
    pending_ = current_;
    pending_duration_s_ = block_.duration_s;
  }
  // As long as the estimate's memory at rest: it stands, and the next block begins where it
  // ended (a bias that drifts over a long rest is followed, not averaged).
  if (block_time_s_ + p_.rest_min_duration_s > p_.bias_time_constant_s) startBlock(has_mag);
  return grown ? News::kLastBlockRevised : News::kNewBlock;
}

}  // namespace headingd::core
