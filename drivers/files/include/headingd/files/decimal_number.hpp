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

// Eight ASCII digits in one word (the first digit in the lowest byte) as their value: each
// step adds neighbouring groups, 1 -> 2 -> 4 -> 8 digits, in three multiplications.
inline std::uint64_t eightDigitsValue(std::uint64_t chunk) {
  chunk = ((chunk & 0x0F0F0F0F0F0F0F0FULL) * 2561) >> 8;
  chunk = ((chunk & 0x00FF00FF00FF00FFULL) * 6553601) >> 16;
  return ((chunk & 0x0000FFFF0000FFFFULL) * 42949672960001ULL) >> 32;
}

// True when all eight bytes are '0'..'9': high nibble 3, low nibble at most 9.
inline bool eightDigits(std::uint64_t chunk) {
  return (chunk & 0xF0F0F0F0F0F0F0F0ULL) == 0x3030303030303030ULL &&
         (((chunk & 0x0F0F0F0F0F0F0F0FULL) + 0x0606060606060606ULL) & 0xF0F0F0F0F0F0F0F0ULL) == 0;
}

// The digits from p on appended to `mantissa` (eight at a time where they are: most of a CSV
// reader's time is here); returns the first non-digit.
[[gnu::always_inline]] inline const char* appendDigits(const char* p, const char* last, std::uint64_t& mantissa) {
  if constexpr (std::endian::native == std::endian::little) {
    std::uint64_t chunk = 0;
    while (last - p >= 8 && (std::memcpy(&chunk, p, 8), eightDigits(chunk))) {
      mantissa = mantissa * 100000000 + eightDigitsValue(chunk);
      p += 8;
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
  const char* p = first;
  const bool negative = p != last && *p == '-';
  if (negative) ++p;
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
  *value = negative ? -magnitude : magnitude;
  return {p, std::errc()};
}


// Writes what printf("%.*f", digits, value) writes (digits 0..9), correctly rounded with ties
// to even as glibc's printf and std::to_chars do, and returns one past the last character.
// |value| * 10^digits below 2^50 is rounded with an exact fma test; larger values, nan and inf
// go to std::to_chars. Needs room for 24 characters, or 340 + digits for huge values.
char* writeFixed(char* out, double value, int digits);

// Writes what printf("%.9g", value) writes: numbers from 0.1 to 1e8 (a recording's time in
// seconds) through writeFixed's rounding, others through std::to_chars. Needs 32 characters.
char* writeGeneral9(char* out, double value);

}  // namespace headingd::files
