#include "headingd/files/decimal_number.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace headingd::files {
namespace {

// 10^0 .. 10^22: every one exact in a double (5^22 < 2^53).
constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                   1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
constexpr std::uint64_t kIntPowersOfTen[] = {1,      10,      100,      1000,      10000,
                                             100000, 1000000, 10000000, 100000000, 1000000000};

bool isDigit(char c) { return static_cast<unsigned char>(c - '0') < 10; }

// Writes `value` as exactly `width` digits with leading zeros.
char* writeDigits(char* out, std::uint64_t value, int width) {
  for (int i = width - 1; i >= 0; --i) {
    out[i] = static_cast<char>('0' + value % 10);
    value /= 10;
  }
  return out + width;
}

}  // namespace

namespace {

// Eight ASCII digits at p, read as one little-endian word and combined pairwise (the SWAR
// technique of D. Lemire's and others' fast number parsers): about 3 multiplications for
// 8 digits instead of 8 dependent multiply-adds. Checks that all 8 bytes are digits.
bool eightDigits(const char* p, std::uint64_t* value) {
  std::uint64_t word;
  std::memcpy(&word, p, 8);
  if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap64(word);
  if ((((word + 0x4646464646464646) | (word - 0x3030303030303030)) & 0x8080808080808080) != 0) return false;
  word = ((word & 0x0F0F0F0F0F0F0F0F) * 2561) >> 8;           // 2561 = 10 * 2^8 + 1: digit pairs
  word = ((word & 0x00FF00FF00FF00FF) * 6553601) >> 16;       // 100 * 2^16 + 1: groups of four
  word = ((word & 0x0000FFFF0000FFFF) * 42949672960001) >> 32;  // 10000 * 2^32 + 1: all eight
  *value = word;
  return true;
}

// Digits from p on into *mantissa; returns one past the last digit, counts them in *count.
const char* readDigits(const char* p, const char* last, std::uint64_t* mantissa, int* count) {
  std::uint64_t eight = 0;
  while (last - p >= 8 && *count <= 11 && eightDigits(p, &eight)) {  // stays below 2^64: 19 digits at most
    *mantissa = *mantissa * 100000000 + eight;
    *count += 8;
    p += 8;
  }
  for (; p != last && isDigit(*p); ++p) {
    if (*count < 19) *mantissa = *mantissa * 10 + static_cast<std::uint64_t>(*p - '0');
    ++*count;  // past 19 digits the mantissa is wrong, and the count sends the number to from_chars
  }
  return p;
}

}  // namespace

std::from_chars_result readDecimal(const char* first, const char* last, double* value) {
  const char* p = first;
  const bool negative = p != last && *p == '-';
  if (negative) ++p;
  std::uint64_t mantissa = 0;
  int digits = 0;  // all digits, leading zeros too (they only make the count safe-side)
  const char* integer_end = readDigits(p, last, &mantissa, &digits);
  int exponent = 0;  // power of ten to apply to the mantissa
  p = integer_end;
  if (p != last && *p == '.') {
    const int before = digits;
    p = readDigits(p + 1, last, &mantissa, &digits);
    exponent = before - digits;
  }
  // No digit, a mantissa that is not exact in a double, or possibly wrapped: the general way.
  if (digits == 0 || digits > 19 || mantissa > (std::uint64_t{1} << 53)) return std::from_chars(first, last, *value);
  if (p != last && (*p == 'e' || *p == 'E')) {
    const char* q = p + 1;
    bool exponent_negative = false;
    if (q != last && (*q == '-' || *q == '+')) exponent_negative = *q++ == '-';
    if (q != last && isDigit(*q)) {  // else "1e" or "1e+": from_chars stops at the 'e', so does this
      int written = 0;
      for (; q != last && isDigit(*q); ++q) {
        if (written > 1000) return std::from_chars(first, last, *value);
        written = written * 10 + (*q - '0');
      }
      exponent += exponent_negative ? -written : written;
      p = q;
    }
  }
  if (exponent < -22 || exponent > 22) return std::from_chars(first, last, *value);
  auto m = static_cast<double>(mantissa);  // exact: at most 2^53
  m = exponent < 0 ? m / kPowersOfTen[-exponent] : m * kPowersOfTen[exponent];
  *value = negative ? -m : m;
  return {p, std::errc()};
}

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
  out = std::to_chars(out, out + 24, n / unit).ptr;
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
