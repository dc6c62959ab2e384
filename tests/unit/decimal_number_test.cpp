// writeFixed and writeGeneral9 against printf, which they stand in for, on the numbers
// estimate rows hold and on the hard cases (exact ties, carries, signs, huge values, nan).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "headingd/files/decimal_number.hpp"

namespace headingd::files {
namespace {

std::string printed(const char* format, double v) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

std::string fixed(double v, int digits) {
  char buffer[512];
  return std::string(buffer, writeFixed(buffer, v, digits));
}

std::string general9(double v) {
  char buffer[512];
  return std::string(buffer, writeGeneral9(buffer, v));
}

void expectLikePrintf(double v) {
  EXPECT_EQ(fixed(v, 9), printed("%.9f", v)) << v;
  EXPECT_EQ(fixed(v, 6), printed("%.6f", v)) << v;
  EXPECT_EQ(fixed(v, 0), printed("%.0f", v)) << v;
  EXPECT_EQ(fixed(v, 3), printed("%.3f", v)) << v;
  EXPECT_EQ(general9(v), printed("%.9g", v)) << v;
}

TEST(WriteNumbers, SameAsPrintfOnHardCases) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const double v : {0.0, -0.0, 1.0, -1.0, 0.5, 1.5, 2.5, -2.5, 1.0 / 1024, 3.0 / 1024, 5e-10, -5e-10, 4e-10,
                         -1e-12, 0.9999999995, 0.99999999949999, 9.9999999995, 99999999.5, 1e8, 1e9, 123456789.0,
                         0.1, 0.09999999999999999, 0.0035, 199.2865, 3188.6365, 1e15, 1e300, -1e300, 5e-324,
                         180.0, -179.9999995, 359.9999999, inf, -inf, std::nan(""), -std::nan("")}) {
    expectLikePrintf(v);
  }
  // Exact ties at 6 and 9 decimals: k / 2^n with few bits.
  for (int k = -4096; k <= 4096; ++k) {
    expectLikePrintf(k / 1024.0);
    expectLikePrintf(k / 64.0);
  }
}

TEST(WriteNumbers, SameAsPrintfOnRandomValues) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(-180.0, 180.0), time(0.0, 1e5);
  std::uniform_int_distribution<int> scale(-12, 12);
  for (int i = 0; i < 100000; ++i) {
    expectLikePrintf(unit(rng));
    expectLikePrintf(angle(rng));
    expectLikePrintf(time(rng));
    expectLikePrintf(unit(rng) * std::pow(10.0, scale(rng)));
    expectLikePrintf(static_cast<double>(i) * 0.0035);  // a recording's time axis
  }
}

}  // namespace
}  // namespace headingd::files
