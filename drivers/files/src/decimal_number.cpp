#include "headingd/files/decimal_number.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace headingd::files {
namespace {

using detail::kPowersOfTen;
constexpr std::uint64_t kIntPowersOfTen[] = {1,      10,      100,      1000,      10000,
                                             100000, 1000000, 10000000, 100000000, 1000000000};

// "00" .. "99": two digits per division, half the divisions of one digit at a time.
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Writes `value` as exactly `width` digits with leading zeros.
char* writeDigits(char* out, std::uint64_t value, int width) {
  int i = width;
  while (i >= 2) {
    i -= 2;
    std::memcpy(out + i, kDigitPairs + 2 * (value % 100), 2);
    value /= 100;
  }
  if (i == 1) out[0] = static_cast<char>('0' + value % 10);
  return out + width;
}

}  // namespace

namespace {

// 2^50: below it the product |value|*10^digits is within 1/8 of the exact one, so the correctly
// rounded integer is n-1, n or n+1 of any n within 5/8 of it.
constexpr double kExactLimit = 1125899906842624.0;

// round(magnitude * 10^digits), ties to even, for a magnitude * 10^digits below kExactLimit.
std::uint64_t roundScaled(double magnitude, int digits) {
  const double scale = kPowersOfTen[digits];
  const double x = magnitude * scale;
  auto n = static_cast<std::int64_t>(x + 0.5);
  const double nd = static_cast<double>(n);
  // x - nd is exact (Sterbenz) and x is within 1/8 of the exact product: a clear case needs
  // no more. Near a half, the signs of exact magnitude*scale - (n ± 1/2) from fma's single
  // rounding decide (an exact sign; zero only when the difference is exactly zero: a tie).
  if (std::fabs(x - nd) < 0.375) return static_cast<std::uint64_t>(n);
  const double above = std::fma(magnitude, scale, -(nd + 0.5));
  const double below = std::fma(magnitude, scale, -(nd - 0.5));
  if (above > 0.0 || (above == 0.0 && (n & 1) != 0)) {
    ++n;
  } else if (below < 0.0 || (below == 0.0 && (n & 1) != 0)) {
    --n;
  }
  return static_cast<std::uint64_t>(n);
}

// n / 10^Digits as "whole.fraction" (the fraction with leading zeros; no '.' for 0 digits).
// A constant Digits turns the divisions into multiplications.
template <int Digits>
char* writeScaledAs(char* out, std::uint64_t n) {
  constexpr std::uint64_t unit = kIntPowersOfTen[Digits];
  const std::uint64_t whole = n / unit;
  if (whole < 10) {  // the common case of quaternion components and small numbers
    *out++ = static_cast<char>('0' + whole);
  } else {
    out = std::to_chars(out, out + 24, whole).ptr;
  }
  if constexpr (Digits == 0) return out;
  *out++ = '.';
  return writeDigits(out, n % unit, Digits);
}

char* writeScaled(char* out, std::uint64_t n, int digits) {
  switch (digits) {
    case 0: return writeScaledAs<0>(out, n);
    case 1: return writeScaledAs<1>(out, n);
    case 2: return writeScaledAs<2>(out, n);
    case 3: return writeScaledAs<3>(out, n);
    case 4: return writeScaledAs<4>(out, n);
    case 5: return writeScaledAs<5>(out, n);
    case 6: return writeScaledAs<6>(out, n);
    case 7: return writeScaledAs<7>(out, n);
    case 8: return writeScaledAs<8>(out, n);
    default: return writeScaledAs<9>(out, n);
  }
}

}  // namespace

char* writeFixed(char* out, double value, int digits) {
  const double magnitude = std::fabs(value);
  if (!(magnitude * kPowersOfTen[digits] < kExactLimit)) {  // nan fails this too
    return std::to_chars(out, out + 340 + digits, value, std::chars_format::fixed, digits).ptr;
  }
  const std::uint64_t n = roundScaled(magnitude, digits);
  if (std::signbit(value)) *out++ = '-';  // printf keeps the sign of -0.0 and of -0.0000001
  return writeScaled(out, n, digits);
}

char* writeGeneral9(char* out, double value) {
  const double magnitude = std::fabs(value);
  // Fixed notation with 0..9 decimals: 9 significant digits of a number from 0.1 to 1e9.
  if (!(magnitude >= 0.1 && magnitude < 1e8)) {
    return std::to_chars(out, out + 32, value, std::chars_format::general, 9).ptr;
  }
  int exponent = -1;  // printf's %e exponent before rounding: 10^exponent <= magnitude
  while (exponent < 8 && magnitude >= kPowersOfTen[exponent + 1]) ++exponent;
  int digits = 8 - exponent;
  std::uint64_t n = roundScaled(magnitude, digits);
  if (n >= kIntPowersOfTen[9]) {  // rounding carried into one more integer digit: one decimal fewer
    --digits;
    n = roundScaled(magnitude, digits);
  }
  if (std::signbit(value)) *out++ = '-';
  out = writeScaled(out, n, digits);
  if (digits == 0) return out;
  while (out[-1] == '0') --out;  // %g drops trailing zeros, and the point with no fraction left
  if (out[-1] == '.') --out;
  return out;
}

}  // namespace headingd::files
