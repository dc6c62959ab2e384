#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/core/toml_document.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <sstream>
#include <toml++/toml.h>

namespace headingd::core {
namespace {

std::string where(const std::string& source, const toml::node& node) {
  return source + ":" + std::to_string(node.source().begin.line);
}

// Reads the keys of one table, checking that each is known and of the expected form.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string source, std::string name, std::set<std::string> known)
      : table_(table), source_(std::move(source)), name_(std::move(name)) {
    for (auto&& [key, node] : table) {
      if (known.count(std::string(key.str())) == 0) {
        std::string list;
        for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
        throw ConfigError(where(source_, node) + ": [" + name_ + "] " + std::string(key.str()) +
                          ": unknown key (expected one of " + list + ")");
      }
    }
  }

  std::string at(const char* key) const { return where(source_, *table_.get(key)) + ": [" + name_ + "] " + key; }
  bool has(const char* key) const { return table_.contains(key); }

  double number(const char* key, const char* expected) const {
    const toml::node& n = *table_.get(key);
    if (!(n.is_floating_point() || n.is_integer())) throw ConfigError(at(key) + ": expected " + expected);
    const double v = *n.value<double>();
    if (!std::isfinite(v)) throw ConfigError(at(key) + ": expected a finite number");
    return v;
  }
  std::int64_t integer(const char* key) const {
    const toml::node& n = *table_.get(key);
    if (!n.is_integer()) throw ConfigError(at(key) + ": expected an integer");
    return *n.value<std::int64_t>();
  }
  std::string text(const char* key) const {
    const toml::node& n = *table_.get(key);
    if (!n.is_string()) throw ConfigError(at(key) + ": expected a string");
    return std::string(*n.value<std::string_view>());
  }
  Vec3 vec3(const char* key, const char* unit) const {
    const toml::array* a = table_.get(key)->as_array();
    const std::string expected = std::string(": expected an array of 3 numbers in ") + unit;
    if (a == nullptr || a->size() != 3) throw ConfigError(at(key) + expected);
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      const toml::node& e = *a->get(static_cast<std::size_t>(i));
      if (!(e.is_floating_point() || e.is_integer()) || !std::isfinite(*e.value<double>())) {
        throw ConfigError(at(key) + expected);
      }
      v(i) = *e.value<double>();
    }
    return v;
  }
  Mat3 mat3(const char* key) const {
    const toml::array* rows = table_.get(key)->as_array();
    const std::string expected = ": expected a 3x3 matrix as a list of 3 rows of 3 numbers";
    if (rows == nullptr || rows->size() != 3) throw ConfigError(at(key) + expected);
    Mat3 m;
    for (int r = 0; r < 3; ++r) {
      const toml::array* row = rows->get(static_cast<std::size_t>(r))->as_array();
      if (row == nullptr || row->size() != 3) throw ConfigError(at(key) + expected);
      for (int c = 0; c < 3; ++c) {
        const toml::node& e = *row->get(static_cast<std::size_t>(c));
        if (!(e.is_floating_point() || e.is_integer()) || !std::isfinite(*e.value<double>())) {
          throw ConfigError(at(key) + expected);
        }
        m(r, c) = *e.value<double>();
      }
    }
    return m;
  }

 private:
  const toml::table& table_;
  std::string source_;
  std::string name_;
};

const toml::table* subTable(const toml::table& doc, const char* name, const std::string& source) {
  const toml::node* n = doc.get(name);
  if (n == nullptr) return nullptr;
  if (!n->is_table()) throw ConfigError(where(source, *n) + ": '" + name + "' must be a table");
  return n->as_table();
}

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  std::string s = buf;
  // Keep it a TOML float (1 → 1.0) so a reader sees the type it expects.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string vec(const Vec3& v) { return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]"; }

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

}  // namespace

ImuCalibration parseImuCalibration(std::string_view toml_text, const std::string& source) {
  toml::table doc = parseTomlDocument(toml_text, source);
  for (auto&& [key, node] : doc) {
    const std::string k(key.str());
    if (k != "calibration" && k != "magnetometer" && k != "gyroscope" && k != "accelerometer" && k != "quality") {
      throw ConfigError(where(source, node) + ": unknown table '" + k +
                        "' (expected calibration, magnetometer, gyroscope, accelerometer, quality)");
    }
  }
  ImuCalibration c;
  if (const toml::table* t = subTable(doc, "calibration", source)) {
    const TableReader r(*t, source, "calibration", {"method", "source_file", "sample_range", "created"});
    if (r.has("method")) c.provenance.method = r.text("method");
    if (r.has("source_file")) c.provenance.source_file = r.text("source_file");
    if (r.has("created")) c.provenance.created = r.text("created");
    if (r.has("sample_range")) {
      const toml::array* a = t->get("sample_range")->as_array();
      if (a == nullptr || a->size() != 2 || !a->get(0)->is_integer() || !a->get(1)->is_integer() ||
          *a->get(0)->value<std::int64_t>() > *a->get(1)->value<std::int64_t>() || *a->get(0)->value<std::int64_t>() < 0) {
        throw ConfigError(r.at("sample_range") + ": expected [first, end) as two integers, 0 <= first <= end");
      }
      c.provenance.first_sample = *a->get(0)->value<std::int64_t>();
      c.provenance.end_sample = *a->get(1)->value<std::int64_t>();
    }
  }
  if (const toml::table* t = subTable(doc, "magnetometer", source)) {
    const TableReader r(*t, source, "magnetometer",
                        {"D", "offset_uT", "field_norm_uT", "field_norm_source", "field_norm_detail", "dip_deg",
                         "noise_sigma_uT"});
    if (r.has("D")) {
      c.mag.D = r.mat3("D");
      const double size = c.mag.D.norm();
      if (!(std::abs(c.mag.D.determinant()) > 1e-9 * size * size * size)) {
        throw ConfigError(r.at("D") + ": expected an invertible matrix (this one is singular)");
      }
    }
    if (r.has("offset_uT")) c.mag.offset_uT = r.vec3("offset_uT", "uT");
    if (r.has("field_norm_uT")) {
      c.mag.field_norm_uT = r.number("field_norm_uT", "a number in uT");
      if (!(c.mag.field_norm_uT > 0.0 && c.mag.field_norm_uT < 1000.0)) {
        throw ConfigError(r.at("field_norm_uT") + ": expected 0 < value < 1000 uT");
      }
    }
    if (r.has("field_norm_source")) {
      const std::string s = r.text("field_norm_source");
      if (s == "wmm") c.mag.field_norm_source = FieldNormSource::kWmm;
      else if (s == "argument") c.mag.field_norm_source = FieldNormSource::kArgument;
      else if (s == "data") c.mag.field_norm_source = FieldNormSource::kData;
      else throw ConfigError(r.at("field_norm_source") + ": expected \"wmm\", \"argument\" or \"data\", got \"" + s + "\"");
    }
    if (r.has("field_norm_detail")) c.mag.field_norm_detail = r.text("field_norm_detail");
    if (r.has("dip_deg")) {
      const double dip = r.number("dip_deg", "a number in degrees");
      if (std::abs(dip) > 90.0) throw ConfigError(r.at("dip_deg") + ": expected -90 .. 90 degrees");
      c.mag.dip_rad = dip * std::numbers::pi / 180.0;
    }
    if (r.has("noise_sigma_uT")) c.mag.noise_sigma_uT = r.vec3("noise_sigma_uT", "uT");
  }
  const auto scaleOf = [](const TableReader& r, const char* key) {
    const Vec3 s = r.vec3(key, "1 (unitless)");
    if (s.minCoeff() <= 0.0) throw ConfigError(r.at(key) + ": expected positive scale factors");
    return s;
  };
  if (const toml::table* t = subTable(doc, "gyroscope", source)) {
    const TableReader r(*t, source, "gyroscope", {"bias_rad_s", "scale", "noise_sigma_rad_s"});
    if (r.has("bias_rad_s")) c.gyro.bias_rad_s = r.vec3("bias_rad_s", "rad/s");
    if (r.has("scale")) c.gyro.scale = scaleOf(r, "scale");
    if (r.has("noise_sigma_rad_s")) c.gyro.noise_sigma_rad_s = r.vec3("noise_sigma_rad_s", "rad/s");
  }
  if (const toml::table* t = subTable(doc, "accelerometer", source)) {
    const TableReader r(*t, source, "accelerometer", {"bias_m_s2", "scale", "noise_sigma_m_s2"});
    if (r.has("bias_m_s2")) c.accel.bias_m_s2 = r.vec3("bias_m_s2", "m/s^2");
    if (r.has("scale")) c.accel.scale = scaleOf(r, "scale");
    if (r.has("noise_sigma_m_s2")) c.accel.noise_sigma_m_s2 = r.vec3("noise_sigma_m_s2", "m/s^2");
  }
  if (const toml::table* t = subTable(doc, "quality", source)) {
    const TableReader r(*t, source, "quality", {"residual_rms_uT", "coverage", "condition_number"});
    if (r.has("residual_rms_uT")) c.provenance.residual_rms_uT = r.number("residual_rms_uT", "a number in uT");
    if (r.has("coverage")) c.provenance.coverage = r.number("coverage", "a fraction 0 .. 1");
    if (r.has("condition_number")) c.provenance.condition_number = r.number("condition_number", "a number");
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
  o << "D = [" << vec(c.mag.D.row(0)) << ",\n     " << vec(c.mag.D.row(1)) << ",\n     " << vec(c.mag.D.row(2)) << "]\n";
  o << "offset_uT = " << vec(c.mag.offset_uT) << "\n";
  if (c.mag.field_norm_uT > 0.0) o << "field_norm_uT = " << num(c.mag.field_norm_uT) << "\n";
  o << "field_norm_source = " << quoted(fieldNormSourceName(c.mag.field_norm_source)) << "\n";
  o << "field_norm_detail = " << quoted(c.mag.field_norm_detail) << "\n";
  if (c.mag.dip_rad) o << "dip_deg = " << num(*c.mag.dip_rad * 180.0 / std::numbers::pi) << "\n";
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
