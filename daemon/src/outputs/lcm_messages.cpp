#include "headingd/daemon/outputs/lcm_messages.hpp"

#include <cmath>
#include <limits>

namespace headingd::daemon {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void copy3(double* out, const core::Vec3& v) {
  for (int i = 0; i < 3; ++i) out[i] = v[i];
}

}  // namespace

void fillHeading(headingd::heading_t& m, const core::HeadingOutput& h, Validity validity, const PublishTimes& t) {
  m.utime = t.utime_us;
  m.sample_utime = t.sample_utime_us;
  m.sample_age_us = t.sample_age_us;
  m.validity = static_cast<std::int8_t>(validity);
  const bool any = validity != Validity::kNone;
  const auto& a = h.attitude;
  m.heading_true_rad = any ? h.heading_true_rad : 0.0;
  m.heading_mag_rad = any ? h.heading_mag_rad : 0.0;
  m.heading_mag_sigma_rad = any ? h.heading_mag_sigma_rad : 0.0;
  m.heading_true_sigma_rad = any ? h.heading_true_sigma_rad : 0.0;
  m.declination_rad = h.declination_rad;
  m.declination_sigma_rad = h.declination_sigma_rad;
  m.declination_sources = static_cast<std::int32_t>(h.declination_sources);
  m.declination_source = core::declinationSourceName(h.declination_sources);
  m.mount_yaw_rad = h.mount_yaw_rad;
  m.mount_yaw_sigma_rad = h.mount_yaw_sigma_rad;
  m.mag_disturbed = a.mag_disturbed;
  m.mag_norm_jump = a.mag_disturbance.norm_jump;
  m.mag_dip_jump = a.mag_disturbance.dip_jump;
  m.mag_norm_reference = a.mag_disturbance.norm_reference;
  m.mag_dip_reference = a.mag_disturbance.dip_reference;
  m.mag_used = a.mag_used;
  m.mag_gain = a.mag_gain;
  m.mag_innovation_rad = a.mag_innovation_rad;
  m.heading_redefined = a.heading_redefined;
}

void fillAttitude(headingd::attitude_t& m, const core::HeadingOutput& h, const core::Mat4& q_covariance,
                  Validity validity, const PublishTimes& t) {
  m.utime = t.utime_us;
  m.sample_utime = t.sample_utime_us;
  m.sample_age_us = t.sample_age_us;
  m.validity = static_cast<std::int8_t>(validity);
  const auto& a = h.attitude;
  m.q_nb[0] = a.q_nb.w();
  m.q_nb[1] = a.q_nb.x();
  m.q_nb[2] = a.q_nb.y();
  m.q_nb[3] = a.q_nb.z();
  const core::EulerAngles euler = core::eulerZyx(a.q_nb);
  m.roll_rad = euler.roll_rad;
  m.pitch_rad = euler.pitch_rad;
  m.yaw_rad = euler.yaw_rad;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m.q_covariance[r][c] = q_covariance(r, c);
  }
  m.motion_level = static_cast<std::int8_t>(a.motion_level);
  m.motion_level_name = core::motionLevelName(a.motion_level);
  m.accel_disturbance = a.accel_disturbance;
  m.at_rest = a.at_rest;
  copy3(m.gyro_bias_rad_s, a.gyro_bias_rad_s);
  m.head_height = a.head_height;
}

void fillImu(headingd::imu_t& m, const core::ImuSample& s, core::SampleVerdict verdict, const std::string& source,
             std::int64_t utime_us) {
  m.utime = utime_us;
  m.sample_utime = s.t_ns / 1000;
  if (m.source != source) m.source = source;
  copy3(m.gyro_rad_s, s.gyro_rad_s);
  copy3(m.accel_m_s2, s.accel_m_s2);
  m.has_mag = s.has_mag;
  if (s.has_mag) {
    copy3(m.mag_uT, s.mag_uT);
  } else {
    m.mag_uT[0] = m.mag_uT[1] = m.mag_uT[2] = 0.0;
  }
  m.verdict = static_cast<std::int8_t>(verdict);
  m.verdict_name = core::sampleVerdictName(verdict);
}

void fillGps(headingd::gps_t& m, const core::GpsObservation& g, const std::string& source, std::int64_t utime_us) {
  m.utime = utime_us;
  m.sample_utime = g.t_ns / 1000;
  if (m.source != source) m.source = source;
  m.fix_ok = g.fix_ok;
  m.has_position = g.position.has_value();
  m.latitude_deg = g.position ? g.position->latitude_deg : kNaN;
  m.longitude_deg = g.position ? g.position->longitude_deg : kNaN;
  m.height_m = g.position ? g.position->height_km * 1e3 : kNaN;
  m.has_course = g.course_rad.has_value();
  m.course_rad = g.course_rad.value_or(kNaN);
  m.has_speed = g.speed_mps.has_value();
  m.speed_mps = g.speed_mps.value_or(kNaN);
  m.has_hdop = g.hdop.has_value();
  m.hdop = g.hdop.value_or(kNaN);
  m.has_magvar = g.magvar_rad.has_value();
  m.magvar_rad = g.magvar_rad.value_or(kNaN);
  m.decimal_year = g.decimal_year.value_or(kNaN);
}

void setStatusCounter(std::vector<headingd::counter_t>& counters, std::size_t i, std::string_view name,
                      std::uint64_t value) {
  if (i >= counters.size()) counters.resize(i + 1);
  if (counters[i].name != name) counters[i].name = name;
  counters[i].value = static_cast<std::int64_t>(value);
}

}  // namespace headingd::daemon
