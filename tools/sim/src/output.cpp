#include "headingd/sim/output.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "headingd/core/angles.hpp"
#include "headingd/core/heading_definition.hpp"
#include "headingd/sim/nmea_writer.hpp"

namespace headingd::sim {

namespace {

using core::kDegPerRad;
using core::Quat;
using core::Vec3;

// Appends text without arguments as it is: printf would read '%' in it, and Debian's
// -Werror=format-security (tools/scripts/build-deb.sh) rejects a non-literal format
// without arguments.
void append(std::string& line, const char* text) { line += text; }

// Appends printf-formatted text to a line.
template <typename... Args>
void append(std::string& line, const char* fmt, Args... args) {
  char buf[512];
  const int n = std::snprintf(buf, sizeof buf, fmt, args...);
  if (n <= 0) return;
  if (static_cast<std::size_t>(n) < sizeof buf) {
    line.append(buf, static_cast<std::size_t>(n));
    return;
  }
  const std::size_t old = line.size();  // longer than the buffer: format in place
  line.resize(old + static_cast<std::size_t>(n) + 1);
  std::snprintf(line.data() + old, static_cast<std::size_t>(n) + 1, fmt, args...);
  line.resize(old + static_cast<std::size_t>(n));
}

double deg360(double rad) {
  double d = std::fmod(rad * kDegPerRad, 360.0);
  if (d < 0.0) d += 360.0;
  return d >= 360.0 ? 0.0 : d;
}

double wrap360(double deg) {
  double d = std::fmod(deg, 360.0);
  if (d < 0.0) d += 360.0;
  return d >= 360.0 ? 0.0 : d;
}

// The sign of a quaternion is free; a fixed choice (w >= 0) keeps the columns continuous
// except where w crosses zero.
Quat canonical(const Quat& q) { return q.w() < 0.0 ? Quat(-q.w(), -q.x(), -q.y(), -q.z()) : q; }

}  // namespace

void writeImuCsv(std::ostream& out, const SimResult& r) {
  out << kImuHeader << '\n';
  std::string line;
  for (const ImuRow& row : r.imu) {
    line.clear();
    const Quat q = canonical(row.q_ns);
    append(line, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9f,%.9f,%.9f,%.9f,%d\n", row.t_s,
           row.gyro_rad_s.x(), row.gyro_rad_s.y(), row.gyro_rad_s.z(), row.accel_m_s2.x(), row.accel_m_s2.y(),
           row.accel_m_s2.z(), row.mag_uT.x(), row.mag_uT.y(), row.mag_uT.z(), q.w(), q.x(), q.y(), q.z(),
           row.moving ? 1 : 0);
    out << line;
  }
}

void writeTruthCsv(std::ostream& out, const SimResult& r) {
  out << kTruthHeader << '\n';
  const LocalFrame frame(r.config.origin);
  std::string line;
  const auto& states = r.trajectory.states;
  for (std::size_t k = 0; k < states.size(); ++k) {
    const TruthState& s = states[k];
    const double heading_true = deg360(core::headingOf(s.q_nb));  // Henriksson definition 2.5.1
    const core::EulerAngles e = core::eulerZyx(s.q_nb);
    const Geodetic g = frame.toGeodetic(s.position_ned_m);
    const Vec3& f = r.field_ned_uT[k];
    const Quat q = canonical(s.q_nb);
    line.clear();
    append(line, "%.6f,%.6f,%.6f,%.6f,%.9f,%.9f,%.6f,%s,%d,%d,", s.t_s, heading_true,
           wrap360(heading_true - r.declination_deg), r.declination_deg, g.latitude_deg, g.longitude_deg,
           r.config.mount_yaw_deg, activityName(s.activity), s.indoor ? 1 : 0, s.moving ? 1 : 0);
    append(line, "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,", e.pitch_rad * kDegPerRad, e.roll_rad * kDegPerRad,
           deg360(core::headingOfAxis(s.q_nb, core::kDocumentedHeadAxis)),
           core::headHeight(s.q_nb, core::kDocumentedHeadAxis), deg360(s.path_heading_rad),
           std::hypot(s.velocity_ned_mps.x(), s.velocity_ned_mps.y()));
    append(line, "%.4f,%.4f,%.4f,%.6f,%.6f,%.6f,%.6f,%.9f,%.9f,%.9f,%.9f,", s.position_ned_m.x(), s.position_ned_m.y(),
           s.position_ned_m.z(), f.x(), f.y(), f.z(), r.disturbance_ned_uT[k].norm(), q.w(), q.x(), q.y(), q.z());
    const Vec3& b = r.imu[k].gyro_bias_rad_s;
    append(line, "%.9g,%.9g,%.9g\n", b.x(), b.y(), b.z());
    out << line;
  }
}

void writeNmea(std::ostream& out, const SimResult& r) {
  NmeaContext c;
  c.clock = {r.config.year, r.config.month, r.config.day, kStartTimeOfDayS};
  c.talker = r.config.talker;
  c.magnetic_variation_deg = r.wmm.declination_deg;  // the receiver knows the model, not the anomaly
  for (const GpsEpoch& e : r.gps) out << nmeaEpoch(e, c);
}

void writeGpsTruthCsv(std::ostream& out, const SimResult& r) {
  out << "t,utc,fix,outlier,lat_deg,lon_deg,speed_mps,course_deg,true_lat_deg,true_lon_deg,true_speed_mps,"
         "true_course_deg,horizontal_error_m\n";
  const LocalFrame frame(r.config.origin);
  const UtcClock clock{r.config.year, r.config.month, r.config.day, kStartTimeOfDayS};
  std::string line;
  for (const GpsEpoch& e : r.gps) {
    line.clear();
    append(line, "%.3f,%s,%d,%d,", e.t_s, utcAt(clock, e.t_s).hhmmss.c_str(), e.fix ? 1 : 0, e.outlier ? 1 : 0);
    if (e.fix) {
      const Vec3 error = frame.toNed(e.position) - frame.toNed(e.true_position);
      append(line, "%.9f,%.9f,%.4f,", e.position.latitude_deg, e.position.longitude_deg, e.speed_mps);
      if (e.course_deg) append(line, "%.4f", *e.course_deg);
      append(line, ",%.9f,%.9f,%.4f,%.4f,%.3f\n", e.true_position.latitude_deg, e.true_position.longitude_deg,
             e.true_speed_mps, e.true_course_deg, std::hypot(error.x(), error.y()));
    } else {
      append(line, ",,,,%.9f,%.9f,%.4f,%.4f,\n", e.true_position.latitude_deg, e.true_position.longitude_deg,
             e.true_speed_mps, e.true_course_deg);
    }
    out << line;
  }
}

void writeSensorErrors(std::ostream& out, const SimResult& r) {
  const SimConfig& c = r.config;
  std::string s;
  append(s, "# headingd-sim: the IMU errors drawn for this run. Each triad reads\n");
  append(s, "#   y = D x + o + b(t) + n   (sensor axes; b drifts from 0, n white with the given sigma)\n");
  append(s, "[run]\nscenario = \"%s\"\nseed = %llu\nimu_grade = \"%s\"\nvector_sampling = \"%s\"\n", c.scenario.c_str(),
         static_cast<unsigned long long>(c.seed), imuGradeName(c.imu_grade), vectorSamplingName(c.vector_sampling));
  append(s, "latitude_deg = %.9g\nlongitude_deg = %.9g\ndate = \"%04d-%02d-%02d\"\n", c.origin.latitude_deg,
         c.origin.longitude_deg, c.year, c.month, c.day);
  append(s, "imu_rate_hz = %.9g\ngps_rate_hz = %.9g\nmount_yaw_deg = %.9g\ndecl_anomaly_deg = %.9g\n", c.imu_rate_hz,
         c.gps_rate_hz, c.mount_yaw_deg, c.decl_anomaly_deg);
  if (c.mount_pitch_deg != 0.0 || c.mount_roll_deg != 0.0) {  // files of runs without them stay as they were
    append(s, "mount_pitch_deg = %.9g\nmount_roll_deg = %.9g\n", c.mount_pitch_deg, c.mount_roll_deg);
  }
  append(s, "duration_s = %.9g\nstart_utc = \"%04d-%02d-%02dT12:00:00Z\"  # the UTC of t = 0\n", r.scenario.durationS(),
         c.year, c.month, c.day);
  append(s, "\n[field]\nwmm_model = \"%s\"\nwmm_declination_deg = %.9g\ndeclination_deg = %.9g\n",
         r.wmm_model_name.c_str(), r.wmm.declination_deg, r.declination_deg);
  append(s, "wmm_inclination_deg = %.9g\nwmm_total_intensity_uT = %.9g\n", r.wmm.inclination_deg, r.wmm.f_nT / 1000.0);
  const auto triad = [&s](const char* name, const DrawnTriad& t, const char* unit) {
    append(s, "\n[%s]  # %s\n", name, unit);
    append(s, "D = [[%.12g, %.12g, %.12g], [%.12g, %.12g, %.12g], [%.12g, %.12g, %.12g]]\n", t.distortion(0, 0),
           t.distortion(0, 1), t.distortion(0, 2), t.distortion(1, 0), t.distortion(1, 1), t.distortion(1, 2),
           t.distortion(2, 0), t.distortion(2, 1), t.distortion(2, 2));
    append(s, "offset = [%.12g, %.12g, %.12g]\n", t.offset.x(), t.offset.y(), t.offset.z());
    append(s, "white_sigma = [%.12g, %.12g, %.12g]\n", t.white_sigma.x(), t.white_sigma.y(), t.white_sigma.z());
    if (t.full_scale > 0.0) append(s, "full_scale = %.9g  # each axis saturates at +-this\n", t.full_scale);
  };
  triad("gyro", r.gyro, "rad/s");
  triad("accel", r.accel, "m/s^2");
  triad("mag", r.mag, "uT");
  if (!r.timing.isDefault()) {
    const SensorTiming& t = r.timing;
    append(s,
           "\n[timing]  # the magnetometer's own rate (its last sample repeated between), its and the "
           "accelerometer's lag behind the gyro\n");
    append(s, "mag_rate_hz = %.9g\nmag_first_sample_s = %.9g\nmag_lag_s = %.9g\naccel_lag_s = %.9g\n", t.mag_rate_hz,
           t.mag_first_sample_s, t.mag_lag_s, t.accel_lag_s);
  }
  out << s;
}

}  // namespace headingd::sim
