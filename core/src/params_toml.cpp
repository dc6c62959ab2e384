#include "headingd/core/params_toml.hpp"

#include <algorithm>
#include <limits>
#include <sstream>
#include <toml++/toml.h>

namespace headingd::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string where(const std::string& source, const toml::source_region& r) {
  std::ostringstream o;
  o << source << ":" << r.begin.line;
  return o.str();
}

// The key written on line `line` (1-based) of `text`, or "" if that line has no `key =`.
std::string keyOnLine(std::string_view text, std::size_t line) {
  for (std::size_t i = 1; i < line && !text.empty(); ++i) {
    const std::size_t nl = text.find('\n');
    text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
  }
  text = text.substr(0, text.find('\n'));
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos) return "";
  std::string_view key = text.substr(0, equals);
  while (!key.empty() && (key.front() == ' ' || key.front() == '\t')) key.remove_prefix(1);
  while (!key.empty() && (key.back() == ' ' || key.back() == '\t')) key.remove_suffix(1);
  return std::string(key);
}

}  // namespace

const std::vector<ParamSpec>& estimatorParamSpecs() {
  using P = EstimatorParams;
  static const std::vector<ParamSpec> specs = {
      {"max_sample_gap_s", &P::max_sample_gap_s, 1e-4, 10.0, "s"},
      {"max_gyro_rad_s", &P::max_gyro_rad_s, 1.0, 1e4, "rad/s"},
      {"max_accel_m_s2", &P::max_accel_m_s2, 10.0, 1e5, "m/s^2"},
      {"max_mag_uT", &P::max_mag_uT, 10.0, 1e6, "uT"},
      {"vector_sample_lag_fraction", &P::vector_sample_lag_fraction, 0.0, 2.0, "1"},
      {"gyro_noise_rad_s", &P::gyro_noise_rad_s, 1e-7, 1.0, "rad/s"},
      {"gyro_scale_noise", &P::gyro_scale_noise, 0.0, 1.0, "1"},
      {"accel_prefilter_time_constant_s", &P::accel_prefilter_time_constant_s, 0.0, 100.0, "s"},
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
      {"redefine_heading_leave", &P::redefine_heading_leave, -1.0, 1.0, "h(q)"},
      {"mag_heading_time_constant_s", &P::mag_heading_time_constant_s, 1e-3, kInf, "s"},
      {"mag_min_horizontal_fraction", &P::mag_min_horizontal_fraction, 0.0, 1.0, "1"},
      {"mag_prefilter_time_constant_s", &P::mag_prefilter_time_constant_s, 0.0, 10.0, "s"},
      {"mag_disturbance_time_constant_s", &P::mag_disturbance_time_constant_s, 1e-3, 600.0, "s"},
      {"mag_max_norm_deviation_uT", &P::mag_max_norm_deviation_uT, 0.0, 1000.0, "uT"},
      {"mag_max_dip_deviation_rad", &P::mag_max_dip_deviation_rad, 0.0, 3.2, "rad"},
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
      {"bias_time_constant_s", &P::bias_time_constant_s, 1e-3, 3600.0, "s"},
      {"bias_motion_time_constant_s", &P::bias_motion_time_constant_s, 0.0, 1e5, "s"},
      {"bias_max_rad_s", &P::bias_max_rad_s, 0.0, 1.0, "rad/s"},
  };
  return specs;
}

EstimatorParams parseEstimatorParams(std::string_view toml_text, const std::string& source) {
  toml::table doc;
  try {
    doc = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream o;
    o << where(source, e.source()) << ": TOML syntax error";
    const std::string key = keyOnLine(toml_text, e.source().begin.line);
    if (!key.empty()) o << " in the value of '" << key << "'";
    o << ": " << e.description();
    throw ConfigError(o.str());
  }
  EstimatorParams p;
  for (auto&& [top_key, top_node] : doc) {
    if (top_key.str() != "estimator") {
      throw ConfigError(where(source, top_node.source()) + ": unknown table or key '" + std::string(top_key.str()) +
                        "' (expected [estimator])");
    }
  }
  const toml::table* table = doc["estimator"].as_table();
  if (table == nullptr) {
    if (doc.contains("estimator")) throw ConfigError(source + ": 'estimator' must be a table");
    return p;
  }
  const auto& specs = estimatorParamSpecs();
  std::map<std::string, int> key_lines;
  for (auto&& [key, node] : *table) {
    key_lines[std::string(key.str())] = static_cast<int>(node.source().begin.line);
    const ParamSpec* spec = nullptr;
    for (const auto& s : specs) {
      if (key.str() == s.key) spec = &s;
    }
    const std::string at = where(source, node.source()) + ": [estimator] " + std::string(key.str());
    if (spec == nullptr) {
      std::string list;
      for (const auto& s : specs) list += (list.empty() ? "" : ", ") + std::string(s.key);
      throw ConfigError(at + ": unknown key (expected one of: " + list + "; config/estimator.toml documents them)");
    }
    const std::optional<double> value = node.value<double>();  // integers convert too
    if (!value || !(node.is_floating_point() || node.is_integer())) {
      throw ConfigError(at + ": expected a number in " + spec->unit);
    }
    if (!(*value >= spec->min && *value <= spec->max)) {
      std::ostringstream o;
      o << at << ": " << *value << " is out of range, expected " << spec->min << " .. " << spec->max << " "
        << spec->unit;
      throw ConfigError(o.str());
    }
    p.*(spec->member) = *value;
  }
  validateEstimatorParams(p, source, &key_lines);
  return p;
}

void validateEstimatorParams(const EstimatorParams& p, const std::string& source,
                             const std::map<std::string, int>* key_lines) {
  // Names the line of whichever of the two keys the file sets (the later one if both).
  auto require = [&](bool ok, const char* key_a, const char* key_b, const char* what) {
    if (ok) return;
    int line = 0;
    if (key_lines != nullptr) {
      for (const char* key : {key_a, key_b}) {
        const auto it = key_lines->find(key);
        if (it != key_lines->end()) line = std::max(line, it->second);
      }
    }
    const std::string at = line > 0 ? source + ":" + std::to_string(line) : source;
    throw ConfigError(at + ": [estimator] " + what);
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
}

}  // namespace headingd::core
