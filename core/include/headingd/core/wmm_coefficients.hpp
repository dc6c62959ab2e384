#pragma once
// World Magnetic Model coefficients parsed from NOAA's COF text layout. Parsing only: the
// caller reads the file (config/wmm/WMM2025.COF), so core stays free of I/O.
//
// Layout: a header line `epoch model-name release-date` (e.g. `2025.0 WMM-2025 11/13/2024`),
// then one line `n m g h dg/dt dh/dt` per Schmidt semi-normalised Gauss coefficient
// (g, h in nT; rates in nT/year), ended by a line of 9s.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace headingd::core {

// Highest degree accepted. The WMM is degree 12 and the high-resolution WMMHR 133; the bound
// keeps a corrupt file from asking for a huge table.
inline constexpr int kWmmMaxDegree = 200;

// A malformed COF document. what() names the source, the 1-based line and what was expected.
class WmmParseError : public std::runtime_error {
 public:
  WmmParseError(const std::string& message, std::size_t line) : std::runtime_error(message), line_(line) {}
  std::size_t line() const { return line_; }

 private:
  std::size_t line_;
};

// One Gauss coefficient pair and its secular variation: g(t) = g + (t - epoch) dg/dt.
struct WmmTerm {
  int n = 0;  // degree, 1..degree
  int m = 0;  // order, 0..n
  double g_nT = 0.0;
  double h_nT = 0.0;  // 0 when m == 0 (there is no sine term)
  double g_rate_nT_per_year = 0.0;
  double h_rate_nT_per_year = 0.0;
};

struct WmmCoefficients {
  double epoch_year = 0.0;   // decimal year the coefficients refer to, e.g. 2025.0
  std::string model_name;    // e.g. "WMM-2025"
  std::string release_date;  // as written in the header, e.g. "11/13/2024"
  int degree = 0;            // highest n, <= kWmmMaxDegree; every (n, m) with 1 <= n <= degree, 0 <= m <= n is present
  std::vector<WmmTerm> terms;  // in file order
};

// Parses `cof_text` (named `source_name` in messages). Throws WmmParseError for a missing or
// malformed header, a line that is not six numbers, n or m out of range, a duplicate or
// missing (n, m), a nonzero h for m = 0, and a document without coefficients. Text after
// the line of 9s is ignored.
WmmCoefficients parseWmmCoefficients(std::string_view cof_text, std::string_view source_name = "WMM COF");

}  // namespace headingd::core
