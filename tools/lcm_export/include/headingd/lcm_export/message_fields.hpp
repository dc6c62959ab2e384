#pragma once
// The fields of headingd's LCM messages (daemon/lcm/*.lcm), in declaration order, for the
// column writer: describeFields(message, writer) calls writer.field("name", message.name)
// for each. Constants are not fields (they are not on the wire). A field added to a .lcm
// file must be added here: tests/lcm_export encodes every exported row again from the .lcm
// declarations and fails on a missing column.
#include "headingd/attitude_t.hpp"
#include "headingd/counter_t.hpp"
#include "headingd/gps_t.hpp"
#include "headingd/heading_t.hpp"
#include "headingd/imu_t.hpp"
#include "headingd/ring_status_t.hpp"
#include "headingd/source_status_t.hpp"
#include "headingd/status_t.hpp"

// HEADINGD_LCM_FIELDS(a, b, ...) is w.field("a", m.a); w.field("b", m.b); ...: each name is
// written once, so a column's name and the member it shows cannot disagree. (A macro loop:
// each HEADINGD_LCM_RESCAN level rescans its argument 4 times, 4^4 = 256 fields at most.)
#define HEADINGD_LCM_RESCAN(...) \
  HEADINGD_LCM_RESCAN3(HEADINGD_LCM_RESCAN3(HEADINGD_LCM_RESCAN3(HEADINGD_LCM_RESCAN3(__VA_ARGS__))))
#define HEADINGD_LCM_RESCAN3(...) \
  HEADINGD_LCM_RESCAN2(HEADINGD_LCM_RESCAN2(HEADINGD_LCM_RESCAN2(HEADINGD_LCM_RESCAN2(__VA_ARGS__))))
#define HEADINGD_LCM_RESCAN2(...) \
  HEADINGD_LCM_RESCAN1(HEADINGD_LCM_RESCAN1(HEADINGD_LCM_RESCAN1(HEADINGD_LCM_RESCAN1(__VA_ARGS__))))
#define HEADINGD_LCM_RESCAN1(...) __VA_ARGS__
#define HEADINGD_LCM_FIELDS(...) __VA_OPT__(HEADINGD_LCM_RESCAN(HEADINGD_LCM_FIELD_EACH(__VA_ARGS__)))
#define HEADINGD_LCM_FIELD_EACH(name, ...) \
  w.field(#name, m.name);                  \
  __VA_OPT__(HEADINGD_LCM_FIELD_AGAIN HEADINGD_LCM_PARENS(__VA_ARGS__))
#define HEADINGD_LCM_PARENS ()
#define HEADINGD_LCM_FIELD_AGAIN() HEADINGD_LCM_FIELD_EACH

namespace headingd::lcm_export {

template <class W>
void describeFields(const headingd::heading_t& m, W& w) {
  HEADINGD_LCM_FIELDS(utime, sample_utime, sample_age_us, validity, heading_true_rad, heading_mag_rad,
                      heading_mag_sigma_rad, heading_true_sigma_rad, declination_rad, declination_sigma_rad,
                      declination_sources, declination_source, mount_yaw_rad, mount_yaw_sigma_rad, mag_disturbed,
                      mag_norm_jump, mag_dip_jump, mag_norm_reference, mag_dip_reference, mag_used, mag_gain,
                      mag_innovation_rad, heading_redefined);
}

template <class W>
void describeFields(const headingd::attitude_t& m, W& w) {
  HEADINGD_LCM_FIELDS(utime, sample_utime, sample_age_us, validity, q_nb, roll_rad, pitch_rad, yaw_rad, q_covariance,
                      motion_level, motion_level_name, accel_disturbance, at_rest, gyro_bias_rad_s, head_height);
}

template <class W>
void describeFields(const headingd::imu_t& m, W& w) {
  HEADINGD_LCM_FIELDS(utime, sample_utime, source, gyro_rad_s, accel_m_s2, has_mag, mag_uT, verdict, verdict_name);
}

template <class W>
void describeFields(const headingd::gps_t& m, W& w) {
  HEADINGD_LCM_FIELDS(utime, sample_utime, source, fix_ok, has_position, latitude_deg, longitude_deg, height_m,
                      has_course, course_rad, has_speed, speed_mps, has_hdop, hdop, has_magvar, magvar_rad,
                      decimal_year);
}

template <class W>
void describeFields(const headingd::counter_t& m, W& w) {
  HEADINGD_LCM_FIELDS(name, value);
}

template <class W>
void describeFields(const headingd::ring_status_t& m, W& w) {
  HEADINGD_LCM_FIELDS(name, capacity, high_water, window_high_water, pushed, dropped);
}

template <class W>
void describeFields(const headingd::source_status_t& m, W& w) {
  HEADINGD_LCM_FIELDS(name, kind, state, last_error, num_counters, counters);
}

template <class W>
void describeFields(const headingd::status_t& m, W& w) {
  HEADINGD_LCM_FIELDS(utime, state, reason, uptime_us, num_sources, sources, num_rings, rings, rate_hz, ticks,
                      deadline_misses, tick_jitter_p50_us, tick_jitter_p99_us, tick_jitter_max_us, processing_p50_us,
                      processing_p99_us, processing_max_us, sample_age_p50_us, sample_age_p99_us, heading_rate_hz,
                      imu_rate_hz, gps_rate_hz, publish_errors, estimator_policy, estimator_priority, driver_policy,
                      driver_priority, memory_locked, num_counters, counters);
}

}  // namespace headingd::lcm_export

#undef HEADINGD_LCM_FIELDS
#undef HEADINGD_LCM_FIELD_EACH
#undef HEADINGD_LCM_FIELD_AGAIN
#undef HEADINGD_LCM_PARENS
#undef HEADINGD_LCM_RESCAN
#undef HEADINGD_LCM_RESCAN3
#undef HEADINGD_LCM_RESCAN2
#undef HEADINGD_LCM_RESCAN1
