// headingd-wmm: the World Magnetic Model field at one place and date, printed as one JSON
// object. Exit codes: 0 done (possibly with a "warning"), 1 the COF file cannot be read or
// parsed, 2 bad arguments.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "headingd/cli/parse_command_line.hpp"
#include "headingd/core/wmm.hpp"
#include "headingd/files/input_file.hpp"

namespace {

using namespace headingd;

constexpr int kExitFileError = 1;
constexpr int kExitBadArguments = 2;

// WMM technical report: the model is specified from 1 km below to 850 km above the ellipsoid.
constexpr double kMinHeight_km = -1.0;
constexpr double kMaxHeight_km = 850.0;

struct BadArgument : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string formatNumber(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", value);
  return buf;
}

// Strict YYYY-MM-DD, so "2025-1-1" or "2025/01/01" are refused rather than misread.
double parseDate(const std::string& text) {
  const bool shape_ok = text.size() == 10 && text[4] == '-' && text[7] == '-';
  for (std::size_t i = 0; shape_ok && i < text.size(); ++i) {
    if (i != 4 && i != 7 && (text[i] < '0' || text[i] > '9')) {
      throw BadArgument("--date: expected YYYY-MM-DD, got '" + text + "'");
    }
  }
  if (!shape_ok) throw BadArgument("--date: expected YYYY-MM-DD, got '" + text + "'");
  try {
    return core::decimalYear(std::stoi(text.substr(0, 4)), std::stoi(text.substr(5, 2)), std::stoi(text.substr(8, 2)));
  } catch (const std::invalid_argument& e) {
    throw BadArgument("--date: " + text + " is not a calendar date (" + e.what() + ")");
  }
}

std::string readFile(const std::string& path) {
  return headingd::files::readWholeFile(path, headingd::files::kWmmFileLimit);  // FileError names the file
}

std::string jsonEscape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "World Magnetic Model field at a geodetic position and date, as one JSON object:\n"
      "X_nT (north), Y_nT (east), Z_nT (down), H_nT, F_nT, incl_deg, decl_deg."};
  double lat_deg = 0.0, lon_deg = 0.0, height_km = 0.0;
  std::string date, cof = HEADINGD_WMM_DEFAULT_COF;
  app.add_option("--lat", lat_deg, "geodetic latitude in degrees, -90..90 (north positive)")->required();
  app.add_option("--lon", lon_deg, "longitude in degrees, -360..360 (east positive)")->required();
  app.add_option("--alt-km", height_km, "height above the WGS-84 ellipsoid in km")->required();
  app.add_option("--date", date, "UTC date, YYYY-MM-DD")->required();
  app.add_option("--cof", cof, "WMM coefficient file in NOAA's COF layout")->capture_default_str();
  app.footer(
      std::string("Exit codes: 0 done (a \"warning\" field flags a date or height outside the model's validity),\n"
                  "1 coefficient file unreadable or malformed, 2 bad arguments.") +
      "\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;

  double decimal_year = 0.0;
  try {
    // NaN passes a plain range check, hence the explicit isfinite.
    if (!std::isfinite(lat_deg) || lat_deg < -90.0 || lat_deg > 90.0) {
      throw BadArgument("--lat: " + formatNumber(lat_deg) + " is outside -90..90 degrees");
    }
    if (!std::isfinite(lon_deg) || lon_deg < -360.0 || lon_deg > 360.0) {
      throw BadArgument("--lon: " + formatNumber(lon_deg) + " is outside -360..360 degrees");
    }
    if (!std::isfinite(height_km)) throw BadArgument("--alt-km: must be a finite number");
    decimal_year = parseDate(date);
  } catch (const BadArgument& e) {
    std::fprintf(stderr, "headingd-wmm: %s\nRun with --help for more information.\n", e.what());
    return kExitBadArguments;
  }

  std::optional<core::WorldMagneticModel> model;
  try {
    model.emplace(core::parseWmmCoefficients(readFile(cof), cof));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-wmm: %s\n", e.what());
    return kExitFileError;
  }

  const core::MagneticFieldElements f = model->field({lat_deg, lon_deg, height_km}, decimal_year);
  std::vector<std::string> warnings;
  if (!f.date_within_validity) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "date %s (%.4f) is outside the validity of %s (%.1f to %.1f)", date.c_str(),
                  decimal_year, model->modelName().c_str(), model->epochYear(), model->validUntilYear());
    warnings.emplace_back(buf);
  }
  if (height_km < kMinHeight_km || height_km > kMaxHeight_km) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "height %.3f km is outside the model's range (%.0f to %.0f km)", height_km,
                  kMinHeight_km, kMaxHeight_km);
    warnings.emplace_back(buf);
  }
  std::string warning;
  for (const auto& w : warnings) warning += (warning.empty() ? "" : "; ") + w;
  if (!warning.empty()) std::fprintf(stderr, "headingd-wmm: warning: %s\n", warning.c_str());

  std::printf(
      "{\"model\":\"%s\",\"decimal_year\":%.6f,\"X_nT\":%.6f,\"Y_nT\":%.6f,\"Z_nT\":%.6f,\"H_nT\":%.6f,"
      "\"F_nT\":%.6f,\"incl_deg\":%.6f,\"decl_deg\":%.6f",
      jsonEscape(model->modelName()).c_str(), decimal_year, f.x_nT, f.y_nT, f.z_nT, f.h_nT, f.f_nT, f.inclination_deg,
      f.declination_deg);
  if (!warning.empty()) std::printf(",\"warning\":\"%s\"", jsonEscape(warning).c_str());
  std::printf("}\n");
  return std::fflush(stdout) == 0 ? 0 : kExitFileError;
}
