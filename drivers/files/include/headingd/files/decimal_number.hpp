#pragma once
// Decimal numbers to and from text, bit for bit as std::from_chars reads and printf writes
// them, faster for the numbers recordings and estimate rows hold (a few significant digits,
// no exponent): with the general routines, reading and writing cost more than the estimator.
#include <charconv>

namespace headingd::files {

// Same result as std::from_chars(first, last, *value), bit for bit. A plain decimal
// ([-]digits[.digits], no exponent) whose digits form an integer m <= 2^53 with k <= 22 of them
// after the point is m / 10^k: one correctly rounded division of two exact doubles (Clinger's
// fast path: W. D. Clinger, "How to read floating point numbers accurately", PLDI 1990).
// Anything else (more digits, an exponent, nan, inf, errors) goes to std::from_chars.
std::from_chars_result readDecimal(const char* first, const char* last, double* value);

// Writes what printf("%.*f", digits, value) writes (digits 0..9), correctly rounded with ties
// to even as glibc's printf and std::to_chars do, and returns one past the last character.
// |value| * 10^digits below 2^50 is rounded with an exact fma test; larger values, nan and inf
// go to std::to_chars. Needs room for 24 characters, or 340 + digits for huge values.
char* writeFixed(char* out, double value, int digits);

// Writes what printf("%.9g", value) writes: numbers from 0.1 to 1e8 (a recording's time in
// seconds) through writeFixed's rounding, others through std::to_chars. Needs 32 characters.
char* writeGeneral9(char* out, double value);

}  // namespace headingd::files
