// readDecimal against std::from_chars, writeFixed against printf: on the
// numbers recordings and estimate rows hold and on the hard cases (long mantissas, exponents,
// exact ties, carries, signs, huge values, nan).
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "headingd/files/decimal_number.hpp"

namespace headingd::files {
namespace {

void expectReadsLikeFromChars(const std::string& text) {
  double expected = -12345.0, got = -12345.0;
  const auto want = std::from_chars(text.data(), text.data() + text.size(), expected);
  const auto have = readDecimal(text.data(), text.data() + text.size(), &got);
  ASSERT_EQ(have.ec, want.ec) << "'" << text << "'";
  if (want.ec != std::errc()) return;
  EXPECT_EQ(have.ptr - text.data(), want.ptr - text.data()) << "'" << text << "'";
  if (std::isnan(expected)) {
    EXPECT_TRUE(std::isnan(got)) << text;
  } else {
    EXPECT_EQ(std::memcmp(&got, &expected, sizeof got), 0) << "'" << text << "': " << got << " vs " << expected;
  }
}

TEST(ReadDecimal, SameAsFromCharsOnChosenForms) {
  for (const char* text : {"0",
                           "-0",
                           "1",
                           "-1",
                           "0.0035",
                           "199.2865",
                           "-0.00106465084",
                           "9.919",
                           "1e2",
                           "1E-5",
                           "1.5e+3",
                           "1e",
                           "1e+",
                           "1e-",
                           "5.",
                           ".5",
                           "-.5",
                           ".",
                           "-",
                           "+1",
                           "",
                           "nan",
                           "-nan",
                           "inf",
                           "-inf",
                           "infinity",
                           "1.2.3",
                           "12a",
                           "0x10",
                           "00000000000000000000001",
                           "1234567890123456789",
                           "12345678901234567890",
                           "9007199254740993",
                           "9007199254740992",
                           "0.1234567890123456789",
                           "1e22",
                           "1e23",
                           "1e-22",
                           "1e-23",
                           "123456789012345e-22",
                           "4.9406564584124654e-324",
                           "1.7976931348623157e308",
                           "1e400",
                           "1e-400",
                           "3.14159265358979",
                           "12345678",
                           "1234567.8",
                           "0.12345678",
                           "-12345678.12345678",
                           "1e0000000000000000000000002",
                           " 1",
                           "1 "}) {
    expectReadsLikeFromChars(text);
  }
}

TEST(ReadDecimal, SameAsFromCharsOnRandomNumbers) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> digits(1, 20), exponent(-30, 30), point(0, 21);
  char buffer[64];
  for (int i = 0; i < 200000; ++i) {
    std::string text = rng() % 2 ? "-" : "";
    const int n = digits(rng), dot = point(rng);
    for (int d = 0; d < n; ++d) {
      if (d == dot) text += '.';
      text += static_cast<char>('0' + rng() % 10);
    }
    if (rng() % 3 == 0) text += "e" + std::to_string(exponent(rng));
    expectReadsLikeFromChars(text);
    // And the shortest form of a random double, as a writer of recordings would produce.
    const double v = std::ldexp(static_cast<double>(rng() >> 11), exponent(rng)) * 1e-16;
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, rng() % 2 ? v : -v).ptr;
    expectReadsLikeFromChars(std::string(buffer, end));
  }
}

// In a CSV line the number is followed by more text: the reader's 8-byte loads run past the
// number's end and must stop at the first non-digit, whatever follows it.
TEST(ReadDecimal, StopsAtTheFieldEndInsideALine) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 100000; ++i) {
    std::string number = rng() % 2 ? "-" : "";
    const int whole = static_cast<int>(rng() % 6), fraction = static_cast<int>(rng() % 19);
    for (int d = 0; d < whole; ++d) number += static_cast<char>('0' + rng() % 10);
    if (fraction > 0 || whole == 0) number += '.';
    for (int d = 0; d < fraction; ++d) number += static_cast<char>('0' + rng() % 10);
    static const char* const kAfter[] = {",", ",123456789012", "\r", " ,7", "e5,1", ".5,1", "x12345678"};
    const std::string line = number + kAfter[rng() % 7] + "0123456789012345";
    expectReadsLikeFromChars(line);
  }
}

std::string printed(const char* format, double v) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

std::string fixed(double v, int digits) {
  char buffer[512];
  return std::string(buffer, writeFixed(buffer, v, digits));
}

void expectLikePrintf(double v) {
  for (int digits = 0; digits <= 9; ++digits) {
    char format[16];
    std::snprintf(format, sizeof format, "%%.%df", digits);
    EXPECT_EQ(fixed(v, digits), printed(format, v)) << v;
  }
}

TEST(WriteNumbers, SameAsPrintfOnHardCases) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const double v : {0.0,
                         -0.0,
                         1.0,
                         -1.0,
                         0.5,
                         1.5,
                         2.5,
                         -2.5,
                         1.0 / 1024,
                         3.0 / 1024,
                         5e-10,
                         -5e-10,
                         4e-10,
                         -1e-12,
                         0.9999999995,
                         0.99999999949999,
                         9.9999999995,
                         99999999.5,
                         1e8,
                         1e9,
                         123456789.0,
                         0.1,
                         0.09999999999999999,
                         0.0035,
                         199.2865,
                         3188.6365,
                         1e15,
                         1e300,
                         -1e300,
                         5e-324,
                         180.0,
                         -179.9999995,
                         359.9999999,
                         inf,
                         -inf,
                         std::nan(""),
                         -std::nan("")}) {
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
