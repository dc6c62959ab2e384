#include "headingd/calibrate/progress.hpp"

#include <chrono>

namespace headingd::calibrate {
namespace {

const auto g_start = std::chrono::steady_clock::now();

}  // namespace

double secondsSinceStart() { return std::chrono::duration<double>(std::chrono::steady_clock::now() - g_start).count(); }

std::string describe(const char* fmt, double a, double b, const std::string& c) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c.c_str());
  return buf;
}

}  // namespace headingd::calibrate
