#pragma once
// Decimal numbers to and from text, bit for bit as std::from_chars reads and printf writes
// them, faster for the numbers recordings and estimate rows hold (a few significant digits,
// no exponent): with the general routines, reading and writing cost more than the estimator.
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>

namespace headingd::files {

namespace detail {

// 10^0 .. 10^22: every one exact in a double (5^22 < 2^53).
inline constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                          1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// Eight ASCII digits in one word (the first digit in the lowest byte; zero bytes count as
// leading zeros) as their value: each step adds neighbouring groups, 1 -> 2 -> 4 -> 8 digits,
// in three multiplications.
inline std::uint64_t eightDigitsValue(std::uint64_t chunk) {
  chunk = ((chunk & 0x0F0F0F0F0F0F0F0FULL) * 2561) >> 8;
  chunk = ((chunk & 0x00FF00FF00FF00FFULL) * 6553601) >> 16;
  return ((chunk & 0x0000FFFF0000FFFFULL) * 42949672960001ULL) >> 32;
}

inline constexpr std::uint64_t kIntPowersOfTen[] = {1,      10,      100,      1000,      10000,
                                                    100000, 1000000, 10000000, 100000000, 1000000000};

// How many of the eight bytes, from the lowest, are '0'..'9' before the first that is not.
// A byte's high bit is set where it is no digit: x = byte ^ '0' is 0..9 for a digit, and
// x + 0x76 reaches 0x80 exactly when x >= 10 (a carry out of a byte only reaches the bytes
// after a non-digit, which do not count).
inline int leadingDigitCount(std::uint64_t chunk) {
  const std::uint64_t x = chunk ^ 0x3030303030303030ULL;
  const std::uint64_t not_digit = ((x + 0x7676767676767676ULL) | x) & 0x8080808080808080ULL;
  return std::countr_zero(not_digit) >> 3;  // 64 >> 3 = 8 when all are digits
}

// The value of the first `count` (0..8) digits of an 8-byte load: moved to its top (the bytes
// shifted in are zeros, which count as leading zeros) and converted at once. Two shifts of
// 32 - 4 count each: one shift of 64 would be undefined.
inline std::uint64_t digitsValue(std::uint64_t chunk, int count) {
  return eightDigitsValue((chunk << (32 - 4 * count)) << (32 - 4 * count));
}

// The digits from p on appended to `mantissa`, a run of up to eight from each 8-byte load,
// without a branch per digit (the count of digits varies at random from number to number: a
// loop per digit is mispredicted once a number). Most of a CSV reader's time is here. Returns
// the first non-digit. (Also converting the next eight bytes before knowing whether they
// count saves a misprediction but costs more instructions than it saves.)
[[gnu::always_inline]] inline const char* appendDigits(const char* p, const char* last, std::uint64_t& mantissa) {
  if constexpr (std::endian::native == std::endian::little) {
    while (last - p >= 8) {
      std::uint64_t chunk = 0;
      std::memcpy(&chunk, p, 8);
      const int count = leadingDigitCount(chunk);
      mantissa = mantissa * kIntPowersOfTen[count] + digitsValue(chunk, count);
      p += count;
      if (count < 8) return p;
    }
  }
  for (; p != last && static_cast<unsigned char>(*p - '0') < 10; ++p) {
    mantissa = mantissa * 10 + static_cast<unsigned char>(*p - '0');
  }
  return p;
}

}  // namespace detail

// Same result as std::from_chars(first, last, *value), bit for bit. A plain decimal
// ([-]digits[.digits], no exponent) whose digits form an integer m <= 2^53 with k <= 22 of them
// after the point is m / 10^k: one correctly rounded division of two exact doubles (Clinger's
// fast path: W. D. Clinger, "How to read floating point numbers accurately", PLDI 1990).
// Anything else (more digits, an exponent, nan, inf, errors) goes to std::from_chars.
// Inline: a CSV reader calls it for every field.
inline std::from_chars_result readDecimal(const char* first, const char* last, double* value) {
  if (first == last) return std::from_chars(first, last, *value);
  const char* p = first;
  const bool negative = *p == '-';
  p += negative;               // no branch: signs come at random
  std::uint64_t mantissa = 0;  // wraps past 19 digits: such numbers go to from_chars below
  const char* digits_start = p;
  p = detail::appendDigits(p, last, mantissa);
  long digits = p - digits_start, decimals = 0;
  if (p != last && *p == '.') {
    const char* decimals_start = ++p;
    p = detail::appendDigits(p, last, mantissa);
    decimals = p - decimals_start;
    digits += decimals;
  }
  if (digits == 0 || digits > 19 || mantissa > (std::uint64_t{1} << 53) || decimals > 22 ||
      (p != last && (*p == 'e' || *p == 'E'))) {
    return std::from_chars(first, last, *value);
  }
  const double magnitude = static_cast<double>(mantissa) / detail::kPowersOfTen[decimals];
  *value = std::bit_cast<double>(std::bit_cast<std::uint64_t>(magnitude) | (std::uint64_t{negative} << 63));
  return {p, std::errc()};
}

// Writes what printf("%.*f", digits, value) writes (digits 0..9), correctly rounded with ties
// to even as glibc's printf and std::to_chars do, and returns one past the last character.
// |value| * 10^digits below 2^50 is rounded with an exact fma test; larger values, nan and inf
// go to std::to_chars. Needs room for 24 characters, or 340 + digits for huge values.
char* writeFixed(char* out, double value, int digits);

// Writes n / 10^digits (digits 0..9) as "whole.fraction" with all `digits` decimals, as
// printf would print that quotient exactly: a count of nanoseconds as seconds, say. Needs room
// for 30 characters.
char* writeScaledDecimal(char* out, std::uint64_t n, int digits);

}  // namespace headingd::files
