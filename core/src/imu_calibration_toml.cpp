#include "headingd/core/imu_calibration_toml.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "headingd/core/angles.hpp"
#include "headingd/core/toml_document.hpp"
#include "headingd/core/toml_table_reader.hpp"

namespace headingd::core {
namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  // Keep it a TOML float (1 → 1.0) so a reader sees the type it expects.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string vec(const Vec3& v) { return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]"; }

// A TOML basic string. Control characters other than tab are not allowed raw in one: they
// are written as escapes, so that any string read from a calibration file is written back
// readable.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\t') || byte == 0x7F) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04X", byte);
      out += escaped;
      continue;
    }
    out += c;
  }
  return out + "\"";
}

}  // namespace

ImuCalibration parseImuCalibration(std::string_view toml_text, const std::string& source) {
  const toml::table doc = parseTomlDocument(toml_text, source);
  rejectUnknownTables(doc, source, {"calibration", "magnetometer", "gyroscope", "accelerometer", "quality"});
  ImuCalibration c;
  TomlTableReader calibration(tableOf(doc, "calibration", source), source, "calibration");
  c.provenance.method = calibration.string("method", c.provenance.method);
  c.provenance.source_file = calibration.string("source_file", c.provenance.source_file);
  c.provenance.created = calibration.string("created", c.provenance.created);
  if (const toml::node* range = calibration.node("sample_range")) {
    const toml::array* a = range->as_array();
    if (a == nullptr || a->size() != 2 || !a->get(0)->is_integer() || !a->get(1)->is_integer() ||
        *a->get(0)->value<std::int64_t>() > *a->get(1)->value<std::int64_t>() ||
        *a->get(0)->value<std::int64_t>() < 0) {
      calibration.fail("sample_range", "expected [first, end) as two integers, 0 <= first <= end");
    }
    c.provenance.first_sample = *a->get(0)->value<std::int64_t>();
    c.provenance.end_sample = *a->get(1)->value<std::int64_t>();
  }
  calibration.rejectUnknownKeys();

  // Values no sensor's calibration has are refused, not applied: a scale factor is within tens
  // of percent of 1 (0.5 .. 2 leaves room for any MEMS part), a gyro bias below 1 rad/s (57°/s),
  // an accelerometer bias below 10 m/s², a hard-iron offset below 5000 µT (beyond every
  // magnetometer's range). A file beyond them is another unit or another file.
  const auto scaleOf = [](TomlTableReader& r, const Vec3& fallback) {
    const Vec3 s = r.vec3("scale", fallback, "1 (unitless)");
    if (s.minCoeff() <= 0.0) r.fail("scale", "expected positive scale factors");
    if (s.minCoeff() < 0.5 || s.maxCoeff() > 2.0) r.fail("scale", "expected scale factors within 0.5 .. 2");
    return s;
  };
  const auto within = [](TomlTableReader& r, const char* key, const Vec3& v, double limit, const char* unit) {
    if (v.cwiseAbs().maxCoeff() > limit) {
      r.fail(key, "expected each component within ±" + num(limit) + " " + unit + " (no sensor's calibration has more)");
    }
  };
  TomlTableReader mag(tableOf(doc, "magnetometer", source), source, "magnetometer");
  c.mag.D = mag.mat3("D", c.mag.D);
  const double size = c.mag.D.norm();
  if (!(std::abs(c.mag.D.determinant()) > 1e-9 * size * size * size)) {
    mag.fail("D", "expected an invertible matrix (this one is singular)");
  }
  c.mag.offset_uT = mag.vec3("offset_uT", c.mag.offset_uT, "uT");
  within(mag, "offset_uT", c.mag.offset_uT, 5000.0, "uT");
  if (mag.has("field_norm_uT")) {
    c.mag.field_norm_uT = mag.finite("field_norm_uT", 0.0, "uT");
    if (!(c.mag.field_norm_uT > 0.0 && c.mag.field_norm_uT < 1000.0))
      mag.fail("field_norm_uT", "expected 0 < value < 1000 uT");
  }
  if (mag.has("field_norm_source")) {
    const std::string s = mag.string("field_norm_source", "");
    if (s == "wmm")
      c.mag.field_norm_source = FieldNormSource::kWmm;
    else if (s == "argument")
      c.mag.field_norm_source = FieldNormSource::kArgument;
    else if (s == "data")
      c.mag.field_norm_source = FieldNormSource::kData;
    else
      mag.fail("field_norm_source", "expected \"wmm\", \"argument\" or \"data\", got \"" + s + "\"");
  }
  c.mag.field_norm_detail = mag.string("field_norm_detail", c.mag.field_norm_detail);
  if (mag.has("dip_deg")) c.mag.dip_rad = mag.number("dip_deg", 0.0, -90.0, 90.0, "degrees") * kRadPerDeg;
  if (mag.has("noise_sigma_uT")) c.mag.noise_sigma_uT = mag.vec3("noise_sigma_uT", Vec3::Zero(), "uT");
  mag.rejectUnknownKeys();

  TomlTableReader gyro(tableOf(doc, "gyroscope", source), source, "gyroscope");
  c.gyro.bias_rad_s = gyro.vec3("bias_rad_s", c.gyro.bias_rad_s, "rad/s");
  within(gyro, "bias_rad_s", c.gyro.bias_rad_s, 1.0, "rad/s");
  c.gyro.scale = scaleOf(gyro, c.gyro.scale);
  if (gyro.has("noise_sigma_rad_s")) c.gyro.noise_sigma_rad_s = gyro.vec3("noise_sigma_rad_s", Vec3::Zero(), "rad/s");
  gyro.rejectUnknownKeys();

  TomlTableReader accel(tableOf(doc, "accelerometer", source), source, "accelerometer");
  c.accel.bias_m_s2 = accel.vec3("bias_m_s2", c.accel.bias_m_s2, "m/s^2");
  within(accel, "bias_m_s2", c.accel.bias_m_s2, 10.0, "m/s^2");
  c.accel.scale = scaleOf(accel, c.accel.scale);
  if (accel.has("noise_sigma_m_s2")) c.accel.noise_sigma_m_s2 = accel.vec3("noise_sigma_m_s2", Vec3::Zero(), "m/s^2");
  accel.rejectUnknownKeys();

  TomlTableReader quality(tableOf(doc, "quality", source), source, "quality");
  if (quality.has("residual_rms_uT")) c.provenance.residual_rms_uT = quality.finite("residual_rms_uT", 0.0, "uT");
  if (quality.has("coverage")) c.provenance.coverage = quality.finite("coverage", 0.0, "(a fraction 0 .. 1)");
  if (quality.has("condition_number")) c.provenance.condition_number = quality.finite("condition_number", 0.0, "1");
  quality.rejectUnknownKeys();
  // A file without one correction (empty, or only provenance) would apply nothing, silently:
  // not a calibration (a partial one, such as a hard-iron offset alone, is).
  if (!mag.has("D") && !mag.has("offset_uT") && !gyro.has("bias_rad_s") && !gyro.has("scale") &&
      !accel.has("bias_m_s2") && !accel.has("scale")) {
    throw ConfigError(source +
                      ": no correction in it: expected at least one of [magnetometer] D or offset_uT, "
                      "[gyroscope] bias_rad_s or scale, [accelerometer] bias_m_s2 or scale (headingd-calibrate "
                      "writes them all)");
  }
  return c;
}

std::string formatImuCalibration(const ImuCalibration& c) {
  std::ostringstream o;
  const auto& p = c.provenance;
  o << "# headingd IMU calibration. Readings are corrected before the estimator:\n"
       "#   gyroscope      w = (w_g - bias) / scale         (Henriksson 2013 eq. 2.41)\n"
       "#   accelerometer  a = (a_a - bias) / scale         (Henriksson eq. 2.40)\n"
       "#   magnetometer   m_b = D^-1 (y_m - offset_uT)     (y_m = D m_b + o, Kok & Schon 2016 eq. 8)\n"
       "# m_b is the field in the IMU's inertial axes, in uT.\n\n";
  o << "[calibration]\n";
  o << "method = " << quoted(p.method) << "\n";
  o << "source_file = " << quoted(p.source_file) << "\n";
  o << "sample_range = [" << p.first_sample << ", " << p.end_sample << "]  # rows used, [first, end)\n";
  o << "created = " << quoted(p.created) << "\n\n";
  o << "[magnetometer]\n";
  o << "D = [" << vec(c.mag.D.row(0)) << ",\n     " << vec(c.mag.D.row(1)) << ",\n     " << vec(c.mag.D.row(2))
    << "]\n";
  o << "offset_uT = " << vec(c.mag.offset_uT) << "\n";
  if (c.mag.field_norm_uT > 0.0) o << "field_norm_uT = " << num(c.mag.field_norm_uT) << "\n";
  o << "field_norm_source = " << quoted(fieldNormSourceName(c.mag.field_norm_source)) << "\n";
  o << "field_norm_detail = " << quoted(c.mag.field_norm_detail) << "\n";
  if (c.mag.dip_rad) o << "dip_deg = " << num(*c.mag.dip_rad * kDegPerRad) << "\n";
  if (c.mag.noise_sigma_uT) o << "noise_sigma_uT = " << vec(*c.mag.noise_sigma_uT) << "\n";
  o << "\n[gyroscope]\n";
  o << "bias_rad_s = " << vec(c.gyro.bias_rad_s) << "\n";
  o << "scale = " << vec(c.gyro.scale) << "\n";
  if (c.gyro.noise_sigma_rad_s) o << "noise_sigma_rad_s = " << vec(*c.gyro.noise_sigma_rad_s) << "\n";
  o << "\n[accelerometer]\n";
  o << "bias_m_s2 = " << vec(c.accel.bias_m_s2) << "\n";
  o << "scale = " << vec(c.accel.scale) << "\n";
  if (c.accel.noise_sigma_m_s2) o << "noise_sigma_m_s2 = " << vec(*c.accel.noise_sigma_m_s2) << "\n";
  if (p.residual_rms_uT || p.coverage || p.condition_number) {
    o << "\n[quality]\n";
    if (p.residual_rms_uT) o << "residual_rms_uT = " << num(*p.residual_rms_uT) << "\n";
    if (p.coverage) o << "coverage = " << num(*p.coverage) << "  # fraction of the sphere visited\n";
    if (p.condition_number) o << "condition_number = " << num(*p.condition_number) << "\n";
  }
  return o.str();
}

}  // namespace headingd::core
