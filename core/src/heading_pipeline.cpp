#include "headingd/core/heading_pipeline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "headingd/core/angles.hpp"

namespace headingd::core {
namespace {

// later - earlier, saturated: corrupt stamps may lie anywhere in the int64 range, and their
// difference must not overflow (it reads as "very long ago" or "far ahead" instead).
std::int64_t elapsedNs(std::int64_t later, std::int64_t earlier) {
  std::int64_t d = 0;
  if (!__builtin_sub_overflow(later, earlier, &d)) return d;
  return later > earlier ? std::numeric_limits<std::int64_t>::max() : std::numeric_limits<std::int64_t>::min();
}

constexpr double kPi = std::numbers::pi;

// The observation with every value the pipeline cannot use left out (counted in `ignored`):
// non-finite numbers, a latitude beyond ±90°, a negative speed or HDOP, a magnetic
// variation beyond ±180°.
// `first_problem` names the first value left out (nullptr when none was).
GpsObservation usableValues(const GpsObservation& gps, std::uint64_t& ignored, const char** first_problem) {
  GpsObservation g = gps;
  const auto drop = [&ignored, first_problem](auto& value, const char* problem) {
    value.reset();
    ++ignored;
    if (*first_problem == nullptr) *first_problem = problem;
  };
  if (g.position && !(std::abs(g.position->latitude_deg) <= 90.0 && std::isfinite(g.position->longitude_deg) &&
                      std::isfinite(g.position->height_km))) {
    drop(g.position, "position beyond ±90° latitude or not finite");
    g.fix_ok = false;  // a fix at an impossible place is no fix
  }
  if (g.decimal_year && !std::isfinite(*g.decimal_year)) drop(g.decimal_year, "date not finite");
  if (g.course_rad && !std::isfinite(*g.course_rad)) drop(g.course_rad, "course not finite");
  if (g.speed_mps && !(*g.speed_mps >= 0.0 && std::isfinite(*g.speed_mps))) {
    drop(g.speed_mps, "speed negative or not finite");
  }
  if (g.hdop && !(*g.hdop >= 0.0 && std::isfinite(*g.hdop))) drop(g.hdop, "HDOP negative or not finite");
  if (g.magvar_rad && !(std::abs(*g.magvar_rad) <= kPi)) {
    drop(g.magvar_rad, "magnetic variation beyond ±180° or not finite");
  }
  return g;
}

}  // namespace

const char* declinationSourceName(unsigned s) {
  static const char* const kNames[8] = {"none",     "wmm",          "gps",          "wmm+gps",
                                        "receiver", "wmm+receiver", "gps+receiver", "wmm+gps+receiver"};
  return kNames[s & 7u];
}

HeadingPipeline::HeadingPipeline(const EstimatorParams& params, const WorldMagneticModel* wmm)
    : p_(params),
      wmm_(wmm),
      estimator_(params),
      gait_(params.gait_window_s),
      course_minus_heading_(params.decl_direction_width_rad, static_cast<int>(params.decl_min_direction_epochs)) {
  if (wmm_ != nullptr) gps_dates_.emplace(*wmm_);
  updateDeclination();  // no source yet: declination unknown (σ = ∞), mounting yaw the prior
}

SampleVerdict HeadingPipeline::process(const ImuSample& s) {
  const SampleVerdict verdict = estimator_.process(s);
  const EstimatorOutput& a = estimator_.output();
  if (verdict != SampleVerdict::kAccepted || a.dt_s <= 0.0) {
    epoch_compass_.restart();
    gait_.restart();
    updateOutput();
    return verdict;
  }
  units_.add(s, a.dt_s);
  if (a.mag_disturbed) {
    last_disturbed_ns_ = s.t_ns;
    ever_disturbed_ = true;
  }
  const Vec3 gyro = s.gyro_rad_s - a.gyro_bias_rad_s;
  // The interval's compass heading is compared with a course only when the interval began at
  // an epoch with a fix and a course (courseGatesPass needs previous_gps_ns_, which only
  // processGps changes). Before the first such epoch, or after one without, the heading would
  // be dropped unread, so the samples are not summed: without GPS the compass costs nothing.
  if (previous_gps_ns_) epoch_compass_.add(gyro, s.accel_m_s2, s.has_mag ? &s.mag_uT : nullptr, a.dt_s);
  const bool walking =
      last_walking_gps_ns_ && elapsedNs(s.t_ns, *last_walking_gps_ns_) < 2'000'000'000 && a.head_height > 0.8;
  if (walking && a.valid) {
    gait_.update(gyro, s.accel_m_s2, a.dt_s);
  } else {
    gait_.restart();
  }
  updateOutput();
  return verdict;
}

bool HeadingPipeline::courseGatesPass(const GpsObservation& gps, double sensor_heading) const {
  const EstimatorOutput& a = estimator_.output();
  if (!gps.fix_ok || !gps.course_rad || !gps.speed_mps || !a.valid) return false;
  if (*gps.speed_mps < p_.decl_min_speed_mps) return false;
  if (gps.hdop && *gps.hdop > p_.decl_max_hdop) return false;
  if (a.head_height < 0.8) return false;  // upright: the x-axis heading is well defined
  if (ever_disturbed_ &&
      elapsedNs(gps.t_ns, last_disturbed_ns_) < static_cast<std::int64_t>(p_.decl_min_undisturbed_s * 1e9)) {
    return false;
  }
  // Walking straight: neither the course nor the magnetic heading turned faster than the
  // limit since the previous epoch (which must be recent).
  if (!previous_gps_ns_) return false;
  const double dt = static_cast<double>(elapsedNs(gps.t_ns, *previous_gps_ns_)) * 1e-9;
  if (!(dt > 0.0 && dt <= 2.0)) return false;
  const double course_rate = std::abs(wrapAngle(*gps.course_rad - previous_course_rad_)) / dt;
  const double heading_rate = std::abs(wrapAngle(sensor_heading - previous_sensor_heading_rad_)) / dt;
  return course_rate <= p_.decl_max_turn_rate_rad_s && heading_rate <= p_.decl_max_turn_rate_rad_s;
}

std::size_t HeadingPipeline::compassMinSamples(std::int64_t gps_t_ns) const {
  // Half the samples the interval since the previous epoch should hold: an interval with
  // a gap in the IMU data gives no compass heading.
  const double period_s = estimator_.output().dt_s;
  if (!previous_gps_ns_ || !(period_s > 0.0)) return 1;
  const double interval_s = static_cast<double>(elapsedNs(gps_t_ns, *previous_gps_ns_)) * 1e-9;
  return static_cast<std::size_t>(std::max(1.0, 0.5 * interval_s / period_s));
}

bool HeadingPipeline::useModelAt(const GeodeticPosition& position, double decimal_year) {
  const MagneticFieldElements field = wmm_->field(position, decimal_year);
  if (!std::isfinite(field.f_nT) || !std::isfinite(field.inclination_deg) || !std::isfinite(field.declination_deg)) {
    return false;
  }
  estimator_.setReferenceField(field.f_nT * 1e-3, field.inclination_deg * kRadPerDeg);
  wmm_declination_rad_ = field.declination_deg * kRadPerDeg;
  return true;
}

bool HeadingPipeline::setPlace(const GeodeticPosition& position, double decimal_year) {
  if (wmm_ == nullptr || !useModelAt(position, decimal_year)) return false;
  gps_dates_->seed(decimal_year);
  updateDeclination();
  updateOutput();
  return true;
}

bool HeadingPipeline::seedGpsDate(double decimal_year) {
  if (wmm_ == nullptr || !wmm_->isDateWithinValidity(decimal_year)) return false;
  gps_dates_->seed(decimal_year);
  return true;
}

const char* HeadingPipeline::processGps(const GpsObservation& given) {
  const char* problem = nullptr;
  GpsObservation gps = usableValues(given, gps_values_ignored_, &problem);
  if (gps.decimal_year && gps_dates_) {
    bool believed = true;
    gps.decimal_year = gps_dates_->dateFor(*gps.decimal_year, gps.t_ns, &believed);
    if (!believed) {
      ++gps_values_ignored_;
      if (problem == nullptr) {
        problem =
            "date outside the World Magnetic Model's validity or far from the date in use (a receiver's default "
            "date, a GPS week-number rollover): the model is evaluated on the date in use";
      }
    }
  }
  const bool model_there = gps.fix_ok && gps.position && gps.decimal_year && wmm_ != nullptr;
  if (model_there && !useModelAt(*gps.position, *gps.decimal_year)) {
    ++gps_values_ignored_;  // a date so far from the model's epoch that the field overflows
    if (problem == nullptr) problem = "date where the World Magnetic Model's field is not finite";
  }
  if (gps.magvar_rad) receiver_magvar_rad_ = *gps.magvar_rad;
  if (gps.fix_ok && gps.speed_mps && *gps.speed_mps >= p_.gait_min_speed_mps) last_walking_gps_ns_ = gps.t_ns;

  // The course is compared with the compass heading over the epoch interval; the filtered
  // heading only gates on turning (it is the smoother of the two from epoch to epoch).
  const double sensor_heading = out_.heading_mag_rad;
  const std::optional<double> compass_heading =
      epoch_compass_.takeHeading(compassMinSamples(gps.t_ns), p_.mag_min_horizontal_fraction);
  const bool added = compass_heading && courseGatesPass(gps, sensor_heading);
  if (added) course_minus_heading_.add(*gps.course_rad, *compass_heading, previous_epoch_added_);
  previous_epoch_added_ = added;
  if (gps.fix_ok && gps.course_rad) {
    previous_gps_ns_ = gps.t_ns;
    previous_course_rad_ = *gps.course_rad;
    previous_sensor_heading_rad_ = sensor_heading;
  } else {
    previous_gps_ns_.reset();
  }
  updateDeclination();
  updateOutput();
  return problem;
}

void HeadingPipeline::updateDeclination() {
  out_.mount_yaw_rad = gait_.mountYawRad();
  out_.mount_yaw_sigma_rad = gait_.hasEstimate() ? gait_.sigmaRad() : p_.mount_yaw_prior_sigma_rad;

  // The WMM and the receiver's magnetic variation are both global models: a local anomaly
  // (iron ore, a city) is an error they share, so together they are no surer than the
  // better of the two. They are averaged into one model source with that σ; counting them as
  // independent would pull the GPS estimate towards the models twice.
  std::array<AngleEstimate, 2> models;
  std::size_t n_models = 0;
  unsigned used = kDeclNone;
  if (wmm_declination_rad_) {
    models[n_models++] = {*wmm_declination_rad_, p_.decl_wmm_sigma_rad};
    used |= kDeclWmm;
  }
  if (receiver_magvar_rad_) {
    models[n_models++] = {*receiver_magvar_rad_, p_.decl_receiver_sigma_rad};
    used |= kDeclReceiver;
  }
  std::array<AngleEstimate, 2> sources;
  std::size_t n = 0;
  if (n_models > 0) {
    AngleEstimate model = fuseAngles(std::span<const AngleEstimate>(models.data(), n_models));
    model.sigma_rad = std::min(p_.decl_wmm_sigma_rad, p_.decl_receiver_sigma_rad);
    if (n_models == 1) model.sigma_rad = models[0].sigma_rad;
    sources[n++] = model;
  }
  AngleEstimate course_minus_heading;
  if (course_minus_heading_.estimate(&course_minus_heading)) {
    // Course - sensor heading = declination - mounting yaw (the sensor's x-axis points at
    // body heading + mounting yaw).
    const double sigma = std::hypot(course_minus_heading.sigma_rad, out_.mount_yaw_sigma_rad);
    sources[n++] = {wrapAngle(course_minus_heading.value_rad + out_.mount_yaw_rad), sigma};
    used |= kDeclGps;
  }
  const AngleEstimate declination = fuseAngles(std::span<const AngleEstimate>(sources.data(), n));
  out_.declination_sources = used;
  out_.declination_rad = used == kDeclNone ? 0.0 : declination.value_rad;
  out_.declination_sigma_rad = declination.sigma_rad;
}

void HeadingOutput::setMagneticHeading(double heading_rad, double sigma_rad) {
  heading_mag_rad = heading_rad;
  heading_true_rad = wrapAngle(heading_mag_rad - mount_yaw_rad + declination_rad);
  heading_mag_sigma_rad = sigma_rad;
  // The three errors are independent: the field's, the gait's and the declination sources'.
  heading_true_sigma_rad =
      std::sqrt(heading_mag_sigma_rad * heading_mag_sigma_rad + mount_yaw_sigma_rad * mount_yaw_sigma_rad +
                declination_sigma_rad * declination_sigma_rad);
}

void HeadingPipeline::updateOutput() {
  out_.attitude = estimator_.output();
  out_.setMagneticHeading(out_.attitude.yaw_rad, out_.attitude.heading_sigma_rad);
}

}  // namespace headingd::core
