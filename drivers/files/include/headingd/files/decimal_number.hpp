#pragma once
// Decimal numbers to and from text, exactly as the standard functions do it, faster for the
// numbers recordings hold (a few significant digits, small exponents): reading a CSV row and
// writing an estimate row cost more than the estimator itself when done by the general routines.
#include <charconv>

namespace headingd::files {

// Same result as std::from_chars(first, last, *value) (chars_format::general), bit for bit.
// A decimal with at most 15 significant digits and a power of ten within ±22 is one correctly
// rounded multiplication or division of two exact doubles (Clinger's fast path: W. D. Clinger,
// "How to read floating point numbers accurately", PLDI 1990); anything else (more digits,
// nan, inf, hex-like forms, errors) goes to std::from_chars.
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
