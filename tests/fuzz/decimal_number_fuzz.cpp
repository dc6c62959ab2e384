// The exact decimal reader and writers against the standard library they promise to match
// bit for bit: readDecimal against std::from_chars on arbitrary text, writeFixed against
// printf("%.*f") on arbitrary doubles.
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "fuzz_check.hpp"
#include "headingd/files/decimal_number.hpp"

using namespace headingd;

namespace {

bool sameDouble(double a, double b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Reading: the input as text.
  const char* first = reinterpret_cast<const char*>(data);
  double ours = 0.0, theirs = 0.0;
  const std::from_chars_result a = files::readDecimal(first, first + size, &ours);
  const std::from_chars_result b = std::from_chars(first, first + size, theirs);
  FUZZ_CHECK(a.ec == b.ec);
  if (a.ec == std::errc()) {
    FUZZ_CHECK(a.ptr == b.ptr);
    FUZZ_CHECK(sameDouble(ours, theirs));
  }

  // Writing: the first 8 bytes as a double, the 9th as the number of decimals.
  if (size < 9) return 0;
  double value = 0.0;
  std::memcpy(&value, data, sizeof value);
  const int digits = data[8] % 10;
  char expected[400], written[400];
  std::snprintf(expected, sizeof expected, "%.*f", digits, value);
  const char* end = files::writeFixed(written, value, digits);
  FUZZ_CHECK(std::string_view(written, static_cast<std::size_t>(end - written)) == expected);
  return 0;
}
