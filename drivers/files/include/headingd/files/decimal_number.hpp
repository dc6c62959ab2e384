#pragma once
// Decimal numbers as text, exactly as printf writes them, two to three times faster than
// printf or std::to_chars for the numbers an estimate row holds (quaternion components,
// angles, a time in seconds): formatting cost more than the estimator itself with printf.
#include <charconv>

namespace headingd::files {

// Writes what printf("%.*f", digits, value) writes (digits 0..9), correctly rounded with ties
// to even as glibc's printf and std::to_chars do, and returns one past the last character.
// |value| * 10^digits below 2^50 is rounded with an exact fma test; larger values, nan and inf
// go to std::to_chars. Needs room for 24 characters, or 340 + digits for huge values.
char* writeFixed(char* out, double value, int digits);

// Writes what printf("%.9g", value) writes: numbers from 0.1 to 1e8 (a recording's time in
// seconds) through writeFixed's rounding, others through std::to_chars. Needs 32 characters.
char* writeGeneral9(char* out, double value);

}  // namespace headingd::files
