#include "headingd/calibrate/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace headingd::calibrate {

namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

// A "nice" tick step (1, 2 or 5 × 10^k) giving about `target` ticks over `span`.
double tickStep(double span, int target) {
  const double raw = span / std::max(1, target);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10.0 * p;
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", std::abs(v) < 1e-12 ? 0.0 : v);
  return b;
}

}  // namespace

SvgPlot::SvgPlot(std::string title, std::string x_label, std::string y_label, int width, int height)
    : title_(std::move(title)),
      x_label_(std::move(x_label)),
      y_label_(std::move(y_label)),
      width_(width),
      height_(height) {}

void SvgPlot::scatter(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour,
                      const std::string& legend) {
  series_.push_back({Series::kScatter, x, y, 0.0, colour, legend});
}
void SvgPlot::line(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour,
                   const std::string& legend) {
  series_.push_back({Series::kLine, x, y, 0.0, colour, legend});
}
void SvgPlot::bars(const std::vector<double>& x, const std::vector<double>& h, double width, const std::string& colour,
                   const std::string& legend) {
  series_.push_back({Series::kBars, x, h, width, colour, legend});
}

std::string SvgPlot::render() const {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const Series& s : series_) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x0 = std::min(x0, s.x[i] - 0.5 * s.bar_width);
      x1 = std::max(x1, s.x[i] + 0.5 * s.bar_width);
      y0 = std::min(y0, s.kind == Series::kBars ? 0.0 : s.y[i]);
      y1 = std::max(y1, s.y[i]);
    }
  }
  if (!(x1 > x0)) x0 -= 1.0, x1 += 1.0;
  if (!(y1 > y0)) y0 -= 1.0, y1 += 1.0;
  const double ml = 55, mr = 15, mt = 28, mb = 42;
  const double pw = width_ - ml - mr, ph = height_ - mt - mb;
  if (equal_aspect_) {  // same units per pixel on both axes (projections of a sphere)
    const double sx = (x1 - x0) / pw, sy = (y1 - y0) / ph, s = std::max(sx, sy);
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    x0 = cx - 0.5 * s * pw, x1 = cx + 0.5 * s * pw, y0 = cy - 0.5 * s * ph, y1 = cy + 0.5 * s * ph;
  }
  const auto px = [&](double x) { return ml + (x - x0) / (x1 - x0) * pw; };
  const auto py = [&](double y) { return mt + ph - (y - y0) / (y1 - y0) * ph; };
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_ << "\" height=\"" << height_
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  o << "<rect x=\"0\" y=\"0\" width=\"" << width_ << "\" height=\"" << height_ << "\" fill=\"white\"/>\n";
  o << "<text x=\"" << width_ / 2 << "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">" << escape(title_)
    << "</text>\n";
  o << "<rect x=\"" << ml << "\" y=\"" << mt << "\" width=\"" << pw << "\" height=\"" << ph
    << "\" fill=\"none\" stroke=\"#444\"/>\n";
  const double xs = tickStep(x1 - x0, 6), ys = tickStep(y1 - y0, 5);
  for (double t = std::ceil(x0 / xs) * xs; t <= x1 + 1e-9 * xs; t += xs) {
    o << "<line x1=\"" << px(t) << "\" y1=\"" << mt + ph << "\" x2=\"" << px(t) << "\" y2=\"" << mt + ph + 4
      << "\" stroke=\"#444\"/><text x=\"" << px(t) << "\" y=\"" << mt + ph + 15 << "\" text-anchor=\"middle\">"
      << num(t) << "</text>\n";
  }
  for (double t = std::ceil(y0 / ys) * ys; t <= y1 + 1e-9 * ys; t += ys) {
    o << "<line x1=\"" << ml - 4 << "\" y1=\"" << py(t) << "\" x2=\"" << ml << "\" y2=\"" << py(t)
      << "\" stroke=\"#444\"/><text x=\"" << ml - 6 << "\" y=\"" << py(t) + 4 << "\" text-anchor=\"end\">" << num(t)
      << "</text>\n";
  }
  o << "<text x=\"" << ml + pw / 2 << "\" y=\"" << height_ - 6 << "\" text-anchor=\"middle\">" << escape(x_label_)
    << "</text>\n";
  o << "<text x=\"12\" y=\"" << mt + ph / 2 << "\" text-anchor=\"middle\" transform=\"rotate(-90 12 " << mt + ph / 2
    << ")\">" << escape(y_label_) << "</text>\n";
  int legend_row = 0;
  for (const Series& s : series_) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    if (s.kind == Series::kScatter) {
      // Thinned to at most 3000 points: the shape is what matters, not every sample.
      const std::size_t step = std::max<std::size_t>(1, n / 3000);
      o << "<g fill=\"" << s.colour << "\" fill-opacity=\"0.5\">";
      for (std::size_t i = 0; i < n; i += step) {
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
          o << "<circle cx=\"" << num(px(s.x[i])) << "\" cy=\"" << num(py(s.y[i])) << "\" r=\"1.3\"/>";
        }
      }
      o << "</g>\n";
    } else if (s.kind == Series::kLine) {
      const std::size_t step = std::max<std::size_t>(1, n / 4000);
      o << "<polyline fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"1.2\" points=\"";
      for (std::size_t i = 0; i < n; i += step) {
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) o << num(px(s.x[i])) << "," << num(py(s.y[i])) << " ";
      }
      o << "\"/>\n";
    } else {
      o << "<g fill=\"" << s.colour << "\" fill-opacity=\"0.6\">";
      for (std::size_t i = 0; i < n; ++i) {
        const double top = py(std::max(s.y[i], 0.0)), bottom = py(0.0);
        o << "<rect x=\"" << num(px(s.x[i] - 0.5 * s.bar_width)) << "\" y=\"" << num(top) << "\" width=\""
          << num(px(s.x[i] + 0.5 * s.bar_width) - px(s.x[i] - 0.5 * s.bar_width)) << "\" height=\"" << num(bottom - top)
          << "\"/>";
      }
      o << "</g>\n";
    }
    if (!s.legend.empty()) {
      const double ly = mt + 12 + 14 * legend_row++;
      o << "<rect x=\"" << ml + 8 << "\" y=\"" << ly - 8 << "\" width=\"10\" height=\"10\" fill=\"" << s.colour
        << "\"/><text x=\"" << ml + 22 << "\" y=\"" << ly + 1 << "\">" << escape(s.legend) << "</text>\n";
    }
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace headingd::calibrate
