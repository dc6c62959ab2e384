#pragma once
// The fields of headingd's LCM messages (daemon/lcm/*.lcm), in declaration order, for the
// column writer. Constants are not fields (they are not on the wire). A field added to a
// .lcm file must be added here: tests/lcm_export checks every table's header against the
// .lcm files.
#include "headingd/attitude_t.hpp"
#include "headingd/counter_t.hpp"
#include "headingd/gps_t.hpp"
#include "headingd/heading_t.hpp"
#include "headingd/imu_t.hpp"
#include "headingd/ring_status_t.hpp"
#include "headingd/source_status_t.hpp"
#include "headingd/status_t.hpp"

namespace headingd::lcm_export {

template <class W>
void describeFields(const headingd::heading_t& m, W& w) {
  w.field("utime", m.utime);
  w.field("sample_utime", m.sample_utime);
  w.field("sample_age_us", m.sample_age_us);
  w.field("validity", m.validity);
  w.field("heading_true_rad", m.heading_true_rad);
  w.field("heading_mag_rad", m.heading_mag_rad);
  w.field("declination_rad", m.declination_rad);
  w.field("declination_sigma_rad", m.declination_sigma_rad);
  w.field("declination_sources", m.declination_sources);
  w.field("declination_source", m.declination_source);
  w.field("mount_yaw_rad", m.mount_yaw_rad);
  w.field("mount_yaw_sigma_rad", m.mount_yaw_sigma_rad);
  w.field("mag_disturbed", m.mag_disturbed);
  w.field("mag_norm_jump", m.mag_norm_jump);
  w.field("mag_dip_jump", m.mag_dip_jump);
  w.field("mag_norm_reference", m.mag_norm_reference);
  w.field("mag_dip_reference", m.mag_dip_reference);
  w.field("mag_used", m.mag_used);
  w.field("mag_gain", m.mag_gain);
  w.field("mag_innovation_rad", m.mag_innovation_rad);
  w.field("heading_redefined", m.heading_redefined);
}

template <class W>
void describeFields(const headingd::attitude_t& m, W& w) {
  w.field("utime", m.utime);
  w.field("sample_utime", m.sample_utime);
  w.field("sample_age_us", m.sample_age_us);
  w.field("validity", m.validity);
  w.field("q_nb", m.q_nb);
  w.field("roll_rad", m.roll_rad);
  w.field("pitch_rad", m.pitch_rad);
  w.field("yaw_rad", m.yaw_rad);
  w.field("q_covariance", m.q_covariance);
  w.field("motion_level", m.motion_level);
  w.field("motion_level_name", m.motion_level_name);
  w.field("accel_disturbance", m.accel_disturbance);
  w.field("at_rest", m.at_rest);
  w.field("gyro_bias_rad_s", m.gyro_bias_rad_s);
  w.field("head_height", m.head_height);
}

template <class W>
void describeFields(const headingd::imu_t& m, W& w) {
  w.field("utime", m.utime);
  w.field("sample_utime", m.sample_utime);
  w.field("source", m.source);
  w.field("gyro_rad_s", m.gyro_rad_s);
  w.field("accel_m_s2", m.accel_m_s2);
  w.field("has_mag", m.has_mag);
  w.field("mag_uT", m.mag_uT);
  w.field("verdict", m.verdict);
  w.field("verdict_name", m.verdict_name);
}

template <class W>
void describeFields(const headingd::gps_t& m, W& w) {
  w.field("utime", m.utime);
  w.field("sample_utime", m.sample_utime);
  w.field("source", m.source);
  w.field("fix_ok", m.fix_ok);
  w.field("has_position", m.has_position);
  w.field("latitude_deg", m.latitude_deg);
  w.field("longitude_deg", m.longitude_deg);
  w.field("height_m", m.height_m);
  w.field("has_course", m.has_course);
  w.field("course_rad", m.course_rad);
  w.field("has_speed", m.has_speed);
  w.field("speed_mps", m.speed_mps);
  w.field("has_hdop", m.has_hdop);
  w.field("hdop", m.hdop);
  w.field("has_magvar", m.has_magvar);
  w.field("magvar_rad", m.magvar_rad);
  w.field("decimal_year", m.decimal_year);
}

template <class W>
void describeFields(const headingd::counter_t& m, W& w) {
  w.field("name", m.name);
  w.field("value", m.value);
}

template <class W>
void describeFields(const headingd::ring_status_t& m, W& w) {
  w.field("name", m.name);
  w.field("capacity", m.capacity);
  w.field("high_water", m.high_water);
  w.field("pushed", m.pushed);
  w.field("dropped", m.dropped);
}

template <class W>
void describeFields(const headingd::source_status_t& m, W& w) {
  w.field("name", m.name);
  w.field("kind", m.kind);
  w.field("state", m.state);
  w.field("last_error", m.last_error);
  w.field("num_counters", m.num_counters);
  w.field("counters", m.counters);
}

template <class W>
void describeFields(const headingd::status_t& m, W& w) {
  w.field("utime", m.utime);
  w.field("state", m.state);
  w.field("reason", m.reason);
  w.field("uptime_us", m.uptime_us);
  w.field("num_sources", m.num_sources);
  w.field("sources", m.sources);
  w.field("num_rings", m.num_rings);
  w.field("rings", m.rings);
  w.field("rate_hz", m.rate_hz);
  w.field("ticks", m.ticks);
  w.field("deadline_misses", m.deadline_misses);
  w.field("tick_jitter_p50_us", m.tick_jitter_p50_us);
  w.field("tick_jitter_p99_us", m.tick_jitter_p99_us);
  w.field("tick_jitter_max_us", m.tick_jitter_max_us);
  w.field("processing_p50_us", m.processing_p50_us);
  w.field("processing_p99_us", m.processing_p99_us);
  w.field("processing_max_us", m.processing_max_us);
  w.field("sample_age_p50_us", m.sample_age_p50_us);
  w.field("sample_age_p99_us", m.sample_age_p99_us);
  w.field("heading_rate_hz", m.heading_rate_hz);
  w.field("imu_rate_hz", m.imu_rate_hz);
  w.field("gps_rate_hz", m.gps_rate_hz);
  w.field("publish_errors", m.publish_errors);
  w.field("num_counters", m.num_counters);
  w.field("counters", m.counters);
}

}  // namespace headingd::lcm_export
