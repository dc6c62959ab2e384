#include "headingd/files/decimal_number.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace headingd::files {
namespace {

using detail::kIntPowersOfTen;
using detail::kPowersOfTen;

// "00" .. "99": two digits per division, half the divisions of one digit at a time.
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// v < 10^8 as eight ASCII digits in one word, the first digit in the lowest byte: the two
// halves of four digits, then the quarters of two, then single digits, each split done in
// every lane at once by a multiply-shift division (exact for these ranges: x/100 as
// x*10486>>20 for x < 10^4, y/10 as y*103>>10 for y < 100). Checked on all 10^8 values.
std::uint64_t eightDigitsText(std::uint32_t v) {
  const std::uint64_t halves = (v / 10000) | (static_cast<std::uint64_t>(v % 10000) << 32);
  const std::uint64_t hundreds = ((halves * 10486) >> 20) & 0x0000007F0000007FULL;
  const std::uint64_t quarters = ((halves - 100 * hundreds) << 16) | hundreds;
  const std::uint64_t tens = ((quarters * 103) >> 10) & 0x000F000F000F000FULL;
  const std::uint64_t digits = ((quarters - 10 * tens) << 8) | tens;
  return digits | 0x3030303030303030ULL;
}

// Writes `value` (below 10^Width) as exactly Width digits with leading zeros.
template <int Width>
char* writeDigits(char* out, std::uint64_t value) {
  static_assert(Width >= 0 && Width <= 9);
  if constexpr (std::endian::native == std::endian::little) {
    if constexpr (Width == 9) {
      *out++ = static_cast<char>('0' + value / 100000000);
      value %= 100000000;
    }
    constexpr int kTail = Width < 8 ? Width : 8;
    const std::uint64_t text = eightDigitsText(static_cast<std::uint32_t>(value));
    char eight[8];
    std::memcpy(eight, &text, 8);
    std::memcpy(out, eight + 8 - kTail, kTail);
    return out + kTail;
  } else {
    int i = Width;
    while (i >= 2) {
      i -= 2;
      std::memcpy(out + i, kDigitPairs + 2 * (value % 100), 2);
      value /= 100;
    }
    if (i == 1) out[0] = static_cast<char>('0' + value % 10);
    return out + Width;
  }
}

// A whole part: one to three digits by table (angles in degrees), more by std::to_chars.
char* writeWhole(char* out, std::uint64_t whole) {
  if (whole < 10) {  // the common case of quaternion components and small numbers
    *out = static_cast<char>('0' + whole);
    return out + 1;
  }
  if (whole < 100) {
    std::memcpy(out, kDigitPairs + 2 * whole, 2);
    return out + 2;
  }
  if (whole < 1000) {
    *out = static_cast<char>('0' + whole / 100);
    std::memcpy(out + 1, kDigitPairs + 2 * (whole % 100), 2);
    return out + 3;
  }
  return std::to_chars(out, out + 24, whole).ptr;
}

}  // namespace

namespace {

// 2^50: below it the product |value|*10^digits is within 1/8 of the exact one, so the correctly
// rounded integer is n-1, n or n+1 of any n within 5/8 of it, and x + 0.5 is exact.
constexpr double kExactLimit = 1125899906842624.0;

// round(magnitude * 10^digits), ties to even, for a magnitude * 10^digits below kExactLimit.
std::uint64_t roundScaled(double magnitude, int digits) {
  const double scale = kPowersOfTen[digits];
  const double x = magnitude * scale;
  auto n = static_cast<std::int64_t>(x + 0.5);
  const double nd = static_cast<double>(n);
  // x - nd is exact (Sterbenz) and x is within half an ulp, at most x 2^-53, of the exact
  // product: when x is that much (twice, to be safe) clear of a half, n is the rounded product.
  // Only near a half do the signs of exact magnitude*scale - (n ± 1/2) from fma's single
  // rounding decide (an exact sign; zero only when the difference is exactly zero: a tie).
  // The narrow margin keeps that branch rare, and so predicted.
  if (std::fabs(x - nd) < 0.5 - x * 0x1p-52) return static_cast<std::uint64_t>(n);
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
  out = writeWhole(out, n / unit);
  if constexpr (Digits == 0) return out;
  *out++ = '.';
  return writeDigits<Digits>(out, n % unit);
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
  *out = '-';                  // printf keeps the sign of -0.0 and of -0.0000001
  out += std::signbit(value);  // no branch: signs come at random
  return writeScaled(out, n, digits);
}

char* writeScaledDecimal(char* out, std::uint64_t n, int digits) { return writeScaled(out, n, digits); }

}  // namespace headingd::files
