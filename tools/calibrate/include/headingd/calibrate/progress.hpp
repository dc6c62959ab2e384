#pragma once
// headingd-calibrate's progress on the terminal (stderr), each line with the seconds since
// the tool started, and the short formatted texts of its notes.
#include <cstdio>
#include <string>

namespace headingd::calibrate {

double secondsSinceStart();

template <typename... Args>
void progress(const char* fmt, Args... args) {
  std::fprintf(stderr, "[%6.2f s] ", secondsSinceStart());
  std::fprintf(stderr, fmt, args...);
  std::fputc('\n', stderr);
}
// Text without arguments, printed as it is (Debian's -Werror=format-security rejects a
// non-literal format without arguments).
inline void progress(const char* text) { progress("%s", text); }

// fmt (printf) with two numbers and a string, at most 255 characters.
std::string describe(const char* fmt, double a, double b, const std::string& c);

}  // namespace headingd::calibrate
