// parseWmmCoefficients: the shipped file, and malformed documents rejected with their line.
#include <gtest/gtest.h>

#include <string>

#include "wmm_test_support.hpp"

namespace {

using namespace headingd;

// A complete degree-2 model: enough to exercise every check without the real table.
const std::string kHeader = "    2025.0            WMM-2025     11/13/2024\n";
const std::string kDegree2 =
    "  1  0  -29351.8       0.0      12.0       0.0\n"
    "  1  1   -1410.8    4545.4       9.7     -21.5\n"
    "  2  0   -2556.6       0.0     -11.6       0.0\n"
    "  2  1    2951.1   -3133.6      -5.2     -27.7\n"
    "  2  2    1649.3    -815.1      -8.0     -12.1\n";
const std::string kEnd =
    "999999999999999999999999999999999999999999999999\n"
    "999999999999999999999999999999999999999999999999\n";

// Expects a WmmParseError at `line` whose message contains `words`.
void expectParseError(const std::string& text, std::size_t line, const std::string& words) {
  try {
    core::parseWmmCoefficients(text, "test.COF");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const core::WmmParseError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    const std::string what = e.what();
    EXPECT_NE(what.find("test.COF:" + std::to_string(line) + ":"), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(WmmCoefficients, ParsesShippedFile) {
  const auto k = core::parseWmmCoefficients(wmm_test::readFile(HEADINGD_WMM_CONFIG_COF));
  EXPECT_DOUBLE_EQ(k.epoch_year, 2025.0);
  EXPECT_EQ(k.model_name, "WMM-2025");
  EXPECT_EQ(k.release_date, "11/13/2024");
  EXPECT_EQ(k.degree, 12);
  ASSERT_EQ(k.terms.size(), 90u);  // Σ_{n=1..12} (n + 1)
  EXPECT_EQ(k.terms.front().n, 1);
  EXPECT_EQ(k.terms.front().m, 0);
  EXPECT_DOUBLE_EQ(k.terms.front().g_nT, -29351.8);
  EXPECT_DOUBLE_EQ(k.terms.front().g_rate_nT_per_year, 12.0);
  EXPECT_DOUBLE_EQ(k.terms[1].h_nT, 4545.4);
  EXPECT_DOUBLE_EQ(k.terms[1].h_rate_nT_per_year, -21.5);
  EXPECT_EQ(k.terms.back().n, 12);
  EXPECT_EQ(k.terms.back().m, 12);
}

TEST(WmmCoefficients, AcceptsCrlfBlankLinesAndMissingTerminator) {
  std::string crlf;
  for (const char c : kHeader + kDegree2 + kEnd) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  EXPECT_EQ(core::parseWmmCoefficients(crlf).terms.size(), 5u);
  EXPECT_EQ(core::parseWmmCoefficients("\n" + kHeader + "\n" + kDegree2).degree, 2);
  // Whatever follows the 9s is not part of the table.
  EXPECT_EQ(core::parseWmmCoefficients(kHeader + kDegree2 + kEnd + "trailing notes\n").terms.size(), 5u);
}

TEST(WmmCoefficients, RejectsMalformedDocuments) {
  expectParseError("", 1, "empty document");
  expectParseError("2025.0 WMM-2025\n" + kDegree2, 1, "header");
  expectParseError("year WMM-2025 11/13/2024\n" + kDegree2, 1, "header");
  expectParseError(kHeader + kEnd, 2, "no coefficients");
  expectParseError(kHeader + "  1  0  -29351.8       0.0      12.0\n", 2, "six numbers");
  expectParseError(kHeader + "  1  0  -29351.8       0.0      12.0  0.0  7\n", 2, "six numbers");
  expectParseError(kHeader + kDegree2 + "  3  0   1361.0x   0.0  -1.3  0.0\n", 7, "six numbers");
  expectParseError(kHeader + "  1  0  nan  0.0  12.0  0.0\n", 2, "finite");
  expectParseError(kHeader + "  0  0  1.0  0.0  0.0  0.0\n", 2, "degree n = 0");
  expectParseError(kHeader + "  201  0  1.0  0.0  0.0  0.0\n", 2, "degree n = 201 outside 1..200");
  expectParseError(kHeader + "  1  2  1.0  0.0  0.0  0.0\n", 2, "order m = 2");
  expectParseError(kHeader + "  1 -1  1.0  0.0  0.0  0.0\n", 2, "order m = -1");
  expectParseError(kHeader + "  1  0  1.0  5.0  0.0  0.0\n", 2, "must be 0 for m = 0");
  expectParseError(kHeader + kDegree2 + "  2  1    2951.1   -3133.6      -5.2     -27.7\n", 7, "duplicate");
  // A hole in the table: (2, 1) missing, reported at the end of the document.
  std::string holed = kDegree2;
  holed.erase(holed.find("  2  1"), holed.find("  2  2") - holed.find("  2  1"));
  expectParseError(kHeader + holed + kEnd, 6, "missing coefficient n = 2, m = 1");
}

TEST(WmmCoefficients, SmallModelEvaluates) {
  // A pure axial dipole (g10 only): at the equator on the reference sphere the field is
  // horizontal and northward with |g10| (WMM report eq. for V with n = 1, m = 0).
  const auto k =
      core::parseWmmCoefficients(kHeader + "  1  0  -30000.0  0.0  0.0  0.0\n  1  1  0.0  0.0  0.0  0.0\n" + kEnd);
  const core::WorldMagneticModel model(k);
  // Geodetic and geocentric latitude agree at the equator; height puts r at 6371.2 km.
  const double height_km = 6371.2 - 6378.137;
  const auto f = model.field({0.0, 0.0, height_km}, 2025.0);
  EXPECT_NEAR(f.x_nT, 30000.0, 1e-6);
  EXPECT_NEAR(f.y_nT, 0.0, 1e-6);
  EXPECT_NEAR(f.z_nT, 0.0, 1e-6);
  EXPECT_NEAR(f.declination_deg, 0.0, 1e-9);
}

}  // namespace
