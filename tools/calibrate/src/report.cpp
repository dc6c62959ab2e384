#include "headingd/calibrate/report.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "headingd/calibrate/svg_plot.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/files/output_file.hpp"

namespace headingd::calibrate {

namespace {

using core::Vec3;

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string projections(const std::vector<Vec3>& points, const std::string& title, const std::string& colour) {
  std::string out;
  const char* names = "xyz";
  for (const auto& [a, b] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
    SvgPlot p(title + " " + names[a] + "-" + names[b], std::string(1, names[a]) + " [uT]",
              std::string(1, names[b]) + " [uT]", 300, 300);
    std::vector<double> x, y;
    for (const Vec3& v : points) x.push_back(v(a)), y.push_back(v(b));
    p.scatter(x, y, colour, "");
    p.equalAspect();
    out += p.render();
  }
  return out;
}

}  // namespace

Verdict judge(const ReportInput& in) {
  Verdict v;
  // Coverage: the fraction of equal-area cells of the sphere the calibrated directions hit.
  if (in.coverage >= 0.5)
    v.coverage = "good: the rotations cover " + fmt("%.0f", 100 * in.coverage) + " % of the sphere";
  else if (in.coverage >= 0.25)
    v.coverage = "fair: " + fmt("%.0f", 100 * in.coverage) +
                 " % of the sphere covered; more turns with other faces up would pin the ellipsoid down better";
  else
    v.coverage =
        "poor: only " + fmt("%.0f", 100 * in.coverage) +
        " % of the sphere covered; the calibration is not trustworthy -- turn the sensor through all directions";
  const std::size_t n = in.residuals.size();
  double mean = 0.0, var = 0.0, c1 = 0.0;
  for (const double r : in.residuals) mean += r;
  mean /= std::max<std::size_t>(1, n);
  for (std::size_t i = 0; i < n; ++i) {
    var += (in.residuals[i] - mean) * (in.residuals[i] - mean);
    if (i > 0) c1 += (in.residuals[i] - mean) * (in.residuals[i - 1] - mean);
  }
  v.residual_mean = mean;
  v.residual_std = n > 1 ? std::sqrt(var / static_cast<double>(n - 1)) : 0.0;
  v.lag1_autocorrelation = var > 0.0 ? c1 / var : 0.0;
  // White noise: |ρ1| within about 2/√n; correlated residuals mean a model error or a
  // disturbance that moved with the sensor.
  const double bound = n > 0 ? 2.0 / std::sqrt(static_cast<double>(n)) : 1.0;
  if (std::abs(v.lag1_autocorrelation) <= std::max(bound, 0.1))
    v.whiteness = "white: lag-1 autocorrelation " + fmt("%.2f", v.lag1_autocorrelation);
  else if (std::abs(v.lag1_autocorrelation) < 0.5)
    v.whiteness = "slightly correlated: lag-1 autocorrelation " + fmt("%.2f", v.lag1_autocorrelation) +
                  " (some model error, or the noise is not white)";
  else
    v.whiteness = "strongly correlated: lag-1 autocorrelation " + fmt("%.2f", v.lag1_autocorrelation) +
                  " -- the model does not explain the data (a disturbance that moved, or a distortion "
                  "that is not constant)";
  if (in.condition_number <= 0.0)
    v.condition = "not computed for this method";
  else if (in.condition_number < 30.0)
    v.condition = "well conditioned (" + fmt("%.0f", in.condition_number) + ")";
  else if (in.condition_number < 100.0)
    v.condition = "moderately conditioned (" + fmt("%.0f", in.condition_number) +
                  "): some parameters are only loosely determined";
  else
    v.condition = "ill conditioned (" + fmt("%.0f", in.condition_number) +
                  "): the data do not determine all parameters; rotate about more axes";
  const bool good = in.coverage >= 0.25 && std::abs(v.lag1_autocorrelation) < 0.5 &&
                    (in.condition_number <= 0.0 || in.condition_number < 100.0);
  v.overall = good ? "usable" : "doubtful: see the points above";
  return v;
}

void writeReport(const std::string& dir, const ReportInput& in) {
  std::filesystem::create_directories(dir);
  const core::ImuCorrection correction(in.calibration);
  std::vector<Vec3> calibrated;
  std::vector<double> norm_raw, norm_cal;
  for (const Vec3& y : in.mag_raw_uT) {
    calibrated.push_back(correction.magnetometer(y));
    norm_raw.push_back(y.norm());
    norm_cal.push_back(calibrated.back().norm());
  }
  const Verdict v = judge(in);
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>headingd calibration report</title>\n"
       "<style>body{font-family:sans-serif;max-width:1000px;margin:auto} svg{margin:4px} "
       "td,th{padding:2px 8px;text-align:left}</style></head><body>\n";
  h << "<h1>Magnetometer calibration: " << in.method << "</h1>\n<p>Data: " << in.source_file << ", "
    << in.mag_raw_uT.size() << " magnetometer samples. Model y<sub>m</sub> = D m<sub>b</sub> + o.</p>\n";
  h << "<h2>Verdict: " << v.overall << "</h2><ul><li>Coverage of the sphere: " << v.coverage
    << "</li><li>Residuals: " << v.whiteness << "; mean " << fmt("%.2f", v.residual_mean) << ", standard deviation "
    << fmt("%.2f", v.residual_std) << " (1 expected)</li><li>Condition: " << v.condition << "</li></ul>\n";
  const auto& m = in.calibration.mag;
  h << "<h2>Result</h2><table><tr><th>D</th><td>";
  for (int r = 0; r < 3; ++r) {
    h << "[" << fmt("%.5f", m.D(r, 0)) << ", " << fmt("%.5f", m.D(r, 1)) << ", " << fmt("%.5f", m.D(r, 2)) << "]<br>";
  }
  h << "</td></tr><tr><th>o [uT]</th><td>[" << fmt("%.3f", m.offset_uT.x()) << ", " << fmt("%.3f", m.offset_uT.y())
    << ", " << fmt("%.3f", m.offset_uT.z()) << "]</td></tr><tr><th>field norm</th><td>" << fmt("%.3f", m.field_norm_uT)
    << " uT (" << core::fieldNormSourceName(m.field_norm_source) << ": " << m.field_norm_detail << ")</td></tr>";
  if (m.dip_rad) h << "<tr><th>dip</th><td>" << fmt("%.2f", *m.dip_rad * core::kDegPerRad) << " deg</td></tr>";
  h << "</table>\n";
  if (!in.notes.empty()) {
    h << "<ul>";
    for (const auto& note : in.notes) h << "<li>" << note << "</li>";
    h << "</ul>\n";
  }
  h << "<h2>Magnetometer data before calibration (K&amp;S Fig. 1)</h2>\n" << projections(in.mag_raw_uT, "raw", "#c33");
  h << "<h2>After calibration (K&amp;S Fig. 3)</h2>\n" << projections(calibrated, "calibrated", "#36c");
  SvgPlot norm("Norm of the magnetometer data (K&S Fig. 4)", "t [s]", "|m| [uT]", 900, 300);
  norm.line(in.t_s, norm_raw, "#c33", "before");
  norm.line(in.t_s, norm_cal, "#36c", "after");
  if (m.field_norm_uT > 0.0 && !in.t_s.empty()) {
    norm.line({in.t_s.front(), in.t_s.back()}, {m.field_norm_uT, m.field_norm_uT}, "#000", "field norm");
  }
  h << "<h2>Norm over time</h2>\n" << norm.render();
  // Histogram of the normalised residuals against the N(0,1) density (Figs. 5-6).
  constexpr int kBins = 41;
  constexpr double kLo = -5.0, kHi = 5.0, kWidth = (kHi - kLo) / kBins;
  std::vector<double> centres(kBins), density(kBins, 0.0), pdf_x, pdf_y;
  for (int i = 0; i < kBins; ++i) centres[static_cast<std::size_t>(i)] = kLo + (i + 0.5) * kWidth;
  std::size_t inside = 0;
  for (const double r : in.residuals) {
    const int b = static_cast<int>(std::floor((r - kLo) / kWidth));
    if (b >= 0 && b < kBins) density[static_cast<std::size_t>(b)] += 1.0, ++inside;
  }
  for (double& d : density) d /= std::max<std::size_t>(1, in.residuals.size()) * kWidth;
  for (double x = kLo; x <= kHi + 1e-9; x += 0.05) {
    pdf_x.push_back(x);
    pdf_y.push_back(std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi));
  }
  SvgPlot hist("Normalised residuals (K&S Figs. 5, 6)", in.residual_kind, "density", 600, 320);
  hist.bars(centres, density, kWidth, "#36c", "residuals");
  hist.line(pdf_x, pdf_y, "#000", "N(0,1)");
  h << "<h2>Residuals</h2>\n"
    << hist.render() << "<p>" << in.residual_kind << "; " << in.residuals.size() - inside << " of "
    << in.residuals.size() << " outside the plotted range.</p>\n";
  h << "</body></html>\n";
  const std::string path = (std::filesystem::path(dir) / "index.html").string();
  files::writeWholeOutputFile(path, h.str());
}

}  // namespace headingd::calibrate
