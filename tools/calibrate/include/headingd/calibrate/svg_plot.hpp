#pragma once
// A small SVG plot writer for the calibration report: axes with ticks, scatter points,
// lines and bars, automatic ranges. Enough for the report's figures, nothing more.
#include <string>
#include <vector>

namespace headingd::calibrate {

class SvgPlot {
 public:
  SvgPlot(std::string title, std::string x_label, std::string y_label, int width = 420, int height = 320);
  void scatter(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour,
               const std::string& legend);
  void line(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour,
            const std::string& legend);
  // Bars of equal width centred on x.
  void bars(const std::vector<double>& x, const std::vector<double>& height, double width, const std::string& colour,
            const std::string& legend);
  void equalAspect() { equal_aspect_ = true; }
  std::string render() const;

 private:
  struct Series {
    enum Kind { kScatter, kLine, kBars } kind;
    std::vector<double> x, y;
    double bar_width;
    std::string colour, legend;
  };
  std::string title_, x_label_, y_label_;
  int width_, height_;
  bool equal_aspect_ = false;
  std::vector<Series> series_;
};

}  // namespace headingd::calibrate
