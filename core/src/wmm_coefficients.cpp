#include "headingd/core/wmm_coefficients.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace headingd::core {
namespace {

constexpr int kMaxDegree = kWmmMaxDegree;

std::vector<std::string_view> splitWhitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

template <typename T>
bool parseWhole(std::string_view token, T& value) {
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc{} && ptr == end;
}

// NOAA ends the table with a line of 9s (two of them in the 2020 and 2025 files).
bool isTerminator(const std::vector<std::string_view>& tokens) {
  if (tokens.size() != 1 || tokens[0].size() < 4) return false;
  return tokens[0].find_first_not_of('9') == std::string_view::npos;
}

class LineError {
 public:
  LineError(std::string_view source, std::size_t line) : source_(source), line_(line) {}
  [[noreturn]] void fail(const std::string& what) const {
    std::ostringstream os;
    os << source_ << ":" << line_ << ": " << what;
    throw WmmParseError(os.str(), line_);
  }

 private:
  std::string_view source_;
  std::size_t line_;
};

int triangularIndex(int n, int m) { return n * (n + 1) / 2 + m; }

}  // namespace

WmmCoefficients parseWmmCoefficients(std::string_view cof_text, std::string_view source_name) {
  WmmCoefficients out;
  bool have_header = false;
  bool terminated = false;
  std::vector<bool> seen(static_cast<std::size_t>(triangularIndex(kMaxDegree, kMaxDegree) + 1), false);
  std::size_t line_no = 0;
  std::size_t pos = 0;

  while (pos < cof_text.size() && !terminated) {
    std::size_t eol = cof_text.find('\n', pos);
    if (eol == std::string_view::npos) eol = cof_text.size();
    std::string_view line = cof_text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // CRLF copies
    const LineError err(source_name, line_no);
    const auto tokens = splitWhitespace(line);
    if (tokens.empty()) continue;

    if (!have_header) {
      if (tokens.size() != 3 || !parseWhole(tokens[0], out.epoch_year) || !std::isfinite(out.epoch_year)) {
        err.fail("expected the header 'epoch model-name release-date' (e.g. '2025.0 WMM-2025 11/13/2024'), got '" +
                 std::string(line) + "'");
      }
      out.model_name = std::string(tokens[1]);
      out.release_date = std::string(tokens[2]);
      have_header = true;
      continue;
    }
    if (isTerminator(tokens)) {
      terminated = true;
      continue;
    }

    WmmTerm t;
    if (tokens.size() != 6 || !parseWhole(tokens[0], t.n) || !parseWhole(tokens[1], t.m) ||
        !parseWhole(tokens[2], t.g_nT) || !parseWhole(tokens[3], t.h_nT) ||
        !parseWhole(tokens[4], t.g_rate_nT_per_year) || !parseWhole(tokens[5], t.h_rate_nT_per_year)) {
      err.fail("expected six numbers 'n m g h dg/dt dh/dt' or a line of 9s, got '" + std::string(line) + "'");
    }
    if (!std::isfinite(t.g_nT) || !std::isfinite(t.h_nT) || !std::isfinite(t.g_rate_nT_per_year) ||
        !std::isfinite(t.h_rate_nT_per_year)) {
      err.fail("coefficients must be finite numbers");
    }
    if (t.n < 1 || t.n > kMaxDegree) {
      err.fail("degree n = " + std::to_string(t.n) + " outside 1.." + std::to_string(kMaxDegree));
    }
    if (t.m < 0 || t.m > t.n) {
      err.fail("order m = " + std::to_string(t.m) + " outside 0..n (n = " + std::to_string(t.n) + ")");
    }
    // A zonal term has no sine part; a value there means the columns are shifted.
    if (t.m == 0 && (t.h_nT != 0.0 || t.h_rate_nT_per_year != 0.0)) {
      err.fail("h and dh/dt must be 0 for m = 0 (n = " + std::to_string(t.n) + ")");
    }
    const auto k = static_cast<std::size_t>(triangularIndex(t.n, t.m));
    if (seen[k]) {
      err.fail("duplicate coefficient n = " + std::to_string(t.n) + ", m = " + std::to_string(t.m));
    }
    seen[k] = true;
    out.degree = std::max(out.degree, t.n);
    out.terms.push_back(t);
  }

  const LineError at_end(source_name, std::max<std::size_t>(line_no, 1));
  if (!have_header) at_end.fail("empty document: expected a WMM COF header and coefficients");
  if (out.terms.empty()) at_end.fail("no coefficients after the header");
  // Every (n, m) up to the degree must be there: a hole would silently be read as 0 nT.
  for (int n = 1; n <= out.degree; ++n) {
    for (int m = 0; m <= n; ++m) {
      if (!seen[static_cast<std::size_t>(triangularIndex(n, m))]) {
        at_end.fail("missing coefficient n = " + std::to_string(n) + ", m = " + std::to_string(m) + " (degree " +
                    std::to_string(out.degree) + ")");
      }
    }
  }
  return out;
}

}  // namespace headingd::core
