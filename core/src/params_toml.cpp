#include "headingd/core/params_toml.hpp"

#include <limits>
#include <sstream>

#include "headingd/core/toml_document.hpp"
#include "headingd/core/toml_table_reader.hpp"

namespace headingd::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

const std::vector<ParamSpec>& estimatorParamSpecs() {
  using P = EstimatorParams;
  static const std::vector<ParamSpec> specs = {
      {"max_sample_gap_s", &P::max_sample_gap_s, 1e-4, 10.0, "s"},
      {"max_gyro_rad_s", &P::max_gyro_rad_s, 1.0, 1e4, "rad/s"},
      {"max_accel_m_s2", &P::max_accel_m_s2, 10.0, 1e5, "m/s^2"},
      {"max_mag_uT", &P::max_mag_uT, 10.0, 1e6, "uT"},
      {"vector_sample_lag_fraction", &P::vector_sample_lag_fraction, 0.0, 2.0, "1"},
      {"mag_delay_max_s", &P::mag_delay_max_s, 0.0, 1.0, "s"},
      {"mag_delay_time_constant_s", &P::mag_delay_time_constant_s, 1.0, 1e5, "s"},
      {"mag_delay_apply_below_sigma_s", &P::mag_delay_apply_below_sigma_s, 0.0, 1.0, "s"},
      {"accel_delay_max_s", &P::accel_delay_max_s, 0.0, 1.0, "s"},
      {"accel_delay_time_constant_s", &P::accel_delay_time_constant_s, 1.0, 1e5, "s"},
      {"accel_delay_apply_below_sigma_s", &P::accel_delay_apply_below_sigma_s, 0.0, 1.0, "s"},
      {"gyro_noise_rad_s", &P::gyro_noise_rad_s, 1e-7, 1.0, "rad/s"},
      {"gyro_scale_noise", &P::gyro_scale_noise, 0.0, 1.0, "1"},
      {"accel_prefilter_time_constant_s", &P::accel_prefilter_time_constant_s, 0.0, 100.0, "s"},
      {"accel_prefilter_turning_time_constant_s", &P::accel_prefilter_turning_time_constant_s, 0.0, 100.0, "s"},
      {"accel_prefilter_full_turn_rate_rad_s", &P::accel_prefilter_full_turn_rate_rad_s, 0.0, 100.0, "rad/s"},
      {"accel_prefilter_turning_max_rate_rad_s", &P::accel_prefilter_turning_max_rate_rad_s, 0.01, 1000.0, "rad/s"},
      {"accel_clip_excess_m_s2", &P::accel_clip_excess_m_s2, 0.0, 1000.0, "m/s^2"},
      {"gravity_m_s2", &P::gravity_m_s2, 9.7, 9.9, "m/s^2"},
      {"accel_disturbance_time_constant_s", &P::accel_disturbance_time_constant_s, 1e-3, 100.0, "s"},
      {"accel_noise_m_s2", &P::accel_noise_m_s2, 1e-4, 1e3, "m/s^2"},
      {"accel_residual_gain", &P::accel_residual_gain, 0.0, 1e6, "1"},
      {"accel_residual_time_constant_s", &P::accel_residual_time_constant_s, 0.0, 100.0, "s"},
      {"disturbance_up_to_walking", &P::disturbance_up_to_walking, 0.0, 1e4, "(m/s^2)^2"},
      {"disturbance_up_to_running", &P::disturbance_up_to_running, 0.0, 1e4, "(m/s^2)^2"},
      {"disturbance_down_to_standing", &P::disturbance_down_to_standing, 0.0, 1e4, "(m/s^2)^2"},
      {"disturbance_down_to_walking", &P::disturbance_down_to_walking, 0.0, 1e4, "(m/s^2)^2"},
      {"backup_reset_period_s", &P::backup_reset_period_s, 0.1, 600.0, "s"},
      {"redefine_heading_enter", &P::redefine_heading_enter, -1.0, 1.0, "h(q)"},
      {"redefine_heading_after_s", &P::redefine_heading_after_s, 0.0, 1e5, "s"},
      {"redefine_heading_leave", &P::redefine_heading_leave, -1.0, 1.0, "h(q)"},
      {"body_up_time_constant_s", &P::body_up_time_constant_s, 0.0, 3600.0, "s"},
      {"body_up_min_walking_s", &P::body_up_min_walking_s, 0.0, 3600.0, "s"},
      {"body_up_relearn_after_s", &P::body_up_relearn_after_s, 0.0, 36000.0, "s"},
      {"mag_heading_time_constant_s", &P::mag_heading_time_constant_s, 1e-3, kInf, "s"},
      {"mag_rate_error_time_constant_s", &P::mag_rate_error_time_constant_s, 0.0, 1e5, "s"},
      {"mag_rate_error_max_turn_rad_s", &P::mag_rate_error_max_turn_rad_s, 0.0, 1e3, "rad/s"},
      {"mag_rate_error_max_reference_age_s", &P::mag_rate_error_max_reference_age_s, 0.0, 1e5, "s"},
      {"mag_rate_error_max_set_aside_share", &P::mag_rate_error_max_set_aside_share, 0.0, 1.0, "1"},
      {"mag_rate_error_settle_s", &P::mag_rate_error_settle_s, 0.0, 1e5, "s"},
      {"mag_rate_error_steady_heading_rad", &P::mag_rate_error_steady_heading_rad, 0.0, 3.2, "rad"},
      {"heading_field_sigma_rad", &P::heading_field_sigma_rad, 0.0, 3.2, "rad"},
      {"heading_field_correlation_s", &P::heading_field_correlation_s, 1e-3, 1e5, "s"},
      {"heading_field_set_aside_share", &P::heading_field_set_aside_share, 0.0, 10.0, "1"},
      {"heading_field_turn_rad", &P::heading_field_turn_rad, 0.0, 100.0, "rad"},
      {"mag_min_horizontal_fraction", &P::mag_min_horizontal_fraction, 0.0, 1.0, "1"},
      {"mag_prefilter_time_constant_s", &P::mag_prefilter_time_constant_s, 0.0, 10.0, "s"},
      {"mag_disturbance_time_constant_s", &P::mag_disturbance_time_constant_s, 1e-3, 600.0, "s"},
      {"mag_back_to_before_s", &P::mag_back_to_before_s, 0.0, 600.0, "s"},
      {"mag_learn_first_s", &P::mag_learn_first_s, 0.0, 600.0, "s"},
      {"mag_learn_new_s", &P::mag_learn_new_s, 0.1, 3600.0, "s"},
      {"mag_max_norm_deviation_uT", &P::mag_max_norm_deviation_uT, 0.0, 1000.0, "uT"},
      {"mag_max_dip_deviation_rad", &P::mag_max_dip_deviation_rad, 0.0, 3.2, "rad"},
      {"mag_residual_hard_iron_uT", &P::mag_residual_hard_iron_uT, 0.0, 1000.0, "uT"},
      {"mag_max_reference_norm_deviation_uT", &P::mag_max_reference_norm_deviation_uT, 0.0, 1000.0, "uT"},
      {"mag_max_reference_dip_deviation_rad", &P::mag_max_reference_dip_deviation_rad, 0.0, 3.2, "rad"},
      {"mag_restore_max_age_s", &P::mag_restore_max_age_s, 0.0, 600.0, "s"},
      {"mag_restore_confirm_s", &P::mag_restore_confirm_s, 0.0, 60.0, "s"},
      {"gait_min_speed_mps", &P::gait_min_speed_mps, 0.0, 20.0, "m/s"},
      {"gait_window_s", &P::gait_window_s, 0.5, 60.0, "s"},
      {"mount_yaw_prior_sigma_rad", &P::mount_yaw_prior_sigma_rad, 0.0, 3.2, "rad"},
      {"decl_min_speed_mps", &P::decl_min_speed_mps, 0.0, 100.0, "m/s"},
      {"decl_max_hdop", &P::decl_max_hdop, 0.5, 100.0, "1"},
      {"decl_max_turn_rate_rad_s", &P::decl_max_turn_rate_rad_s, 0.0, 10.0, "rad/s"},
      {"decl_min_undisturbed_s", &P::decl_min_undisturbed_s, 0.0, 600.0, "s"},
      {"decl_direction_width_rad", &P::decl_direction_width_rad, 0.01, 3.2, "rad"},
      {"decl_min_direction_epochs", &P::decl_min_direction_epochs, 1.0, 1e6, "epochs"},
      {"decl_wmm_sigma_rad", &P::decl_wmm_sigma_rad, 1e-4, 3.2, "rad"},
      {"decl_receiver_sigma_rad", &P::decl_receiver_sigma_rad, 1e-4, 3.2, "rad"},
      {"rest_gyro_threshold_rad_s", &P::rest_gyro_threshold_rad_s, 0.0, 1.0, "rad/s"},
      {"rest_gyro_max_threshold_rad_s", &P::rest_gyro_max_threshold_rad_s, 0.0, 10.0, "rad/s"},
      {"rest_accel_threshold_m_s2", &P::rest_accel_threshold_m_s2, 0.0, 10.0, "m/s^2"},
      {"rest_min_duration_s", &P::rest_min_duration_s, 0.0, 60.0, "s"},
      {"rest_filter_time_constant_s", &P::rest_filter_time_constant_s, 1e-3, 60.0, "s"},
      {"rest_max_turn_rate_rad_s", &P::rest_max_turn_rate_rad_s, 0.0, 1.0, "rad/s"},
      {"bias_walk_rad_s_per_sqrt_s", &P::bias_walk_rad_s_per_sqrt_s, 1e-9, 1.0, "rad/s/sqrt(s)"},
      {"bias_instability_rad_s", &P::bias_instability_rad_s, 0.0, 1.0, "rad/s"},
      {"bias_instability_time_s", &P::bias_instability_time_s, 1e-3, 1e5, "s"},
      {"bias_time_constant_s", &P::bias_time_constant_s, 1e-3, 3600.0, "s"},
      {"bias_motion_time_constant_s", &P::bias_motion_time_constant_s, 0.0, 1e5, "s"},
      {"bias_motion_max_attitude_change", &P::bias_motion_max_attitude_change, 0.0, 10.0, "1"},
      {"bias_motion_min_tilt_lags", &P::bias_motion_min_tilt_lags, 0.0, 100.0, "tilt time constants"},
      {"bias_max_rad_s", &P::bias_max_rad_s, 0.0, 1.0, "rad/s"},
      {"qsf_mag_window_s", &P::qsf_mag_window_s, 0.0, 60.0, "s"},
      {"qsf_mag_reference_s", &P::qsf_mag_reference_s, 0.0, 60.0, "s"},
      {"qsf_mag_max_norm_rms_uT", &P::qsf_mag_max_norm_rms_uT, 0.0, 1000.0, "uT"},
      {"qsf_mag_max_norm_deviation_uT", &P::qsf_mag_max_norm_deviation_uT, 0.0, 1000.0, "uT"},
      {"qsf_mag_max_direction_rms_uT", &P::qsf_mag_max_direction_rms_uT, 0.0, 1000.0, "uT"},
      {"qsf_accel_window_s", &P::qsf_accel_window_s, 0.0, 60.0, "s"},
      {"qsf_accel_reference_s", &P::qsf_accel_reference_s, 0.0, 60.0, "s"},
      {"qsf_accel_max_norm_rms_m_s2", &P::qsf_accel_max_norm_rms_m_s2, 0.0, 100.0, "m/s^2"},
      {"qsf_accel_max_norm_deviation_m_s2", &P::qsf_accel_max_norm_deviation_m_s2, 0.0, 100.0, "m/s^2"},
      {"qsf_accel_max_direction_rms_m_s2", &P::qsf_accel_max_direction_rms_m_s2, 0.0, 100.0, "m/s^2"},
      {"qsf_mag_update_noise_uT", &P::qsf_mag_update_noise_uT, 0.0, 1000.0, "uT"},
      {"mau_noise_uT", &P::mau_noise_uT, 0.0, 1000.0, "uT"},
      {"mau_interval_s", &P::mau_interval_s, 0.0, 3600.0, "s"},
      {"maru_baseline_s", &P::maru_baseline_s, 0.0, 600.0, "s"},
      {"agu_baseline_s", &P::agu_baseline_s, 0.0, 600.0, "s"},
      {"agu_residual_accel_bias_m_s2", &P::agu_residual_accel_bias_m_s2, 0.0, 100.0, "m/s^2"},
      {"mau_verify_max_rad", &P::mau_verify_max_rad, 0.0, 3.15, "rad"},
      {"field_update_max_nis", &P::field_update_max_nis, 0.0, 1e6, "1"},
  };
  return specs;
}

EstimatorParams parseEstimatorTable(const toml::table* estimator, const std::string& source) {
  TomlTableReader r(estimator, source, "estimator");
  EstimatorParams p;
  for (const ParamSpec& spec : estimatorParamSpecs()) {
    p.*(spec.member) = r.number(spec.key, p.*(spec.member), spec.min, spec.max, spec.unit);
  }
  r.rejectUnknownKeys("config/estimator.toml documents them");
  validateEstimatorParams(p, r);
  return p;
}

EstimatorParams parseEstimatorParams(std::string_view toml_text, const std::string& source) {
  const toml::table doc = parseTomlDocument(toml_text, source);
  for (auto&& [key, node] : doc) {
    if (key.str() != "estimator") {
      throw ConfigError(sourceLine(source, node) + ": unknown table or key '" + std::string(key.str()) +
                        "' (expected [estimator])");
    }
  }
  return parseEstimatorTable(tableOf(doc, "estimator", source), source);
}

void validateEstimatorParams(const EstimatorParams& p, const TomlTableReader& r) {
  // Each check names the line of whichever of its two keys the file sets (the later one).
  auto require = [&r](bool ok, const char* key_a, const char* key_b, const std::string& what) {
    if (!ok) r.failBetween(key_a, key_b, what);
  };
  require(p.disturbance_down_to_standing < p.disturbance_up_to_walking, "disturbance_down_to_standing",
          "disturbance_up_to_walking",
          "disturbance_down_to_standing must be below disturbance_up_to_walking (hysteresis)");
  require(p.disturbance_down_to_walking < p.disturbance_up_to_running, "disturbance_down_to_walking",
          "disturbance_up_to_running",
          "disturbance_down_to_walking must be below disturbance_up_to_running (hysteresis)");
  require(p.disturbance_up_to_walking < p.disturbance_up_to_running, "disturbance_up_to_walking",
          "disturbance_up_to_running", "disturbance_up_to_walking must be below disturbance_up_to_running");
  require(p.rest_gyro_threshold_rad_s <= p.rest_gyro_max_threshold_rad_s, "rest_gyro_threshold_rad_s",
          "rest_gyro_max_threshold_rad_s", "rest_gyro_threshold_rad_s must not exceed rest_gyro_max_threshold_rad_s");
  require(p.redefine_heading_enter < p.redefine_heading_leave, "redefine_heading_enter", "redefine_heading_leave",
          "redefine_heading_enter must be below redefine_heading_leave (hysteresis)");
  // ξ_ref is the mean of the period's first samples, which are in its first window.
  require(p.qsf_mag_reference_s <= p.qsf_mag_window_s, "qsf_mag_reference_s", "qsf_mag_window_s",
          "qsf_mag_reference_s must not exceed qsf_mag_window_s (the reference norm comes from the first window)");
  require(p.qsf_accel_reference_s <= p.qsf_accel_window_s, "qsf_accel_reference_s", "qsf_accel_window_s",
          "qsf_accel_reference_s must not exceed qsf_accel_window_s (the reference norm comes from the first window)");
  // The two background headings restart every period, staggered by half of it, so the older
  // one is always between half a period and a period old (heading_corrections.hpp): a
  // maximum age below half the period would never let the restore happen.
  std::ostringstream restore;
  restore << "mag_restore_max_age_s = " << p.mag_restore_max_age_s << " s is below half of backup_reset_period_s ("
          << p.backup_reset_period_s << " s): the older background heading is always at least "
          << 0.5 * p.backup_reset_period_s << " s old, so the restore could never happen; expected 0 (restore off) or "
          << 0.5 * p.backup_reset_period_s << " s or more";
  require(p.mag_restore_max_age_s == 0.0 || p.mag_restore_max_age_s >= 0.5 * p.backup_reset_period_s,
          "mag_restore_max_age_s", "backup_reset_period_s", restore.str());
}

void validateEstimatorParams(const EstimatorParams& p, const std::string& source) {
  validateEstimatorParams(p, TomlTableReader(nullptr, source, "estimator"));
}

}  // namespace headingd::core
