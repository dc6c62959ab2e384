// The numeric CSV reader (CsvRowReader: LineReader, the one-pass fast path, the exact field
// by field path) on arbitrary files, plain or gzip (whole or cut anywhere). Invariants: only
// CsvError is thrown; for plain files, every row handed out holds exactly the values a
// straightforward reading of its line gives (split at commas, trim, from_chars), and
// readNumericCsv agrees with the row reader.
#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_check.hpp"
#include "headingd/files/csv_row_reader.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "memory_file.hpp"

using namespace headingd;

namespace {

const std::vector<std::string> kRequired = {"t"};
const std::vector<std::string> kOptional = {"gyr_x", "acc_z"};
// A column asked for twice takes the exact path for every row.
const std::vector<std::string> kOptionalTwice = {"gyr_x", "acc_z", "t"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view s, char separator) {
  std::vector<std::string_view> parts;
  for (std::size_t start = 0;;) {
    const std::size_t at = s.find(separator, start);
    parts.push_back(s.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) return parts;
    start = at + 1;
  }
}

// The value of `field` as the format defines it, or nullopt-like false.
bool referenceValue(std::string_view field, double* value) {
  field = trim(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return false;
  const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), *value);
  return ec == std::errc() && ptr == field.data() + field.size();
}

bool sameDouble(double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; }

std::string gzip(std::string_view text) {
  z_stream z{};
  if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) std::abort();
  std::string out(deflateBound(&z, text.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  if (deflate(&z, Z_FINISH) != Z_STREAM_END) std::abort();
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  // First byte: 0 plain (fast path), 1 plain (exact path), 2 gzip, 3 gzip cut to the
  // fraction second byte / 255 of its length. The rest is the file's text.
  const int kind = data[0] % 4;
  const bool gzipped = kind >= 2;
  const std::vector<std::string>& optional = kind == 1 ? kOptionalTwice : kOptional;
  const std::string text(reinterpret_cast<const char*>(data + 2), size - 2);
  std::string file = gzipped ? gzip(text) : text;
  if (kind == 3) file.resize(file.size() * data[1] / 255);
  const MemoryFile memory(file.data(), file.size());

  const std::vector<std::string_view> lines = split(text, '\n');
  std::vector<std::vector<double>> rows;
  try {
    files::CsvRowReader reader(memory.path(), kRequired, optional);
    FUZZ_CHECK(reader.columns().size() >= 1 && reader.columns()[0] == "t");
    std::vector<double> values(reader.columns().size());
    while (reader.next(values)) {
      rows.push_back(values);
      if (kind == 3) continue;  // a cut stream may end inside a line
      // The row's line, checked field by field.
      FUZZ_CHECK(reader.lineNumber() >= 2 && reader.lineNumber() <= lines.size());
      const std::vector<std::string_view> fields = split(lines[reader.lineNumber() - 1], ',');
      for (std::size_t slot = 0; slot < values.size(); ++slot) {
        const auto& header = reader.header();
        const std::size_t index =
            static_cast<std::size_t>(std::find(header.begin(), header.end(), reader.columns()[slot]) - header.begin());
        double expected = 0.0;
        FUZZ_CHECK(index < fields.size() && referenceValue(fields[index], &expected));
        FUZZ_CHECK(sameDouble(values[slot], expected));
      }
    }
    FUZZ_CHECK(reader.rows() == rows.size());
  } catch (const files::CsvError&) {
    return 0;
  }
  // The whole-file reader reads the same file to the same columns (each name once: it keys
  // them by name).
  const files::NumericCsv whole = files::readNumericCsv(memory.path(), kRequired, kOptional);
  FUZZ_CHECK(whole.rows == rows.size());
  const std::vector<double>& t = whole.column("t");
  for (std::size_t i = 0; i < rows.size(); ++i) FUZZ_CHECK(sameDouble(t[i], rows[i][0]));
  return 0;
}
