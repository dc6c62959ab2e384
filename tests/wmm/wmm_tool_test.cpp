// headingd-wmm end to end: the real binary, real files, its JSON and its exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "wmm_test_support.hpp"

namespace {

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

RunResult runTool(const std::string& args) {
  const auto err_path =
      std::filesystem::temp_directory_path() / ("headingd-wmm-test-" + std::to_string(::getpid()) + ".stderr");
  const std::string cmd = shellQuote(HEADINGD_WMM_TOOL) + " " + args + " 2>" + shellQuote(err_path.string());
  RunResult r;
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) throw std::runtime_error("popen failed: " + cmd);
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = headingd::wmm_test::readFile(err_path.string());
  std::filesystem::remove(err_path);
  return r;
}

// The number after "key": in a flat JSON object; NaN when the key is absent.
double jsonNumber(const std::string& json, const std::string& key) {
  const std::string needle = "\"" + key + "\":";
  const auto pos = json.find(needle);
  if (pos == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + pos + needle.size(), nullptr);
}

bool looksLikeOneJsonObject(const std::string& out) {
  return out.size() > 2 && out.front() == '{' && out.substr(out.size() - 2) == "}\n" &&
         out.find('\n') == out.size() - 1;
}

// NOAA WMM2025 test value: 2025.0, 65 km, 43 N, 93 E.
TEST(WmmTool, ReproducesNoaaTestPoint) {
  const auto r = runTool("--lat 43 --lon 93 --alt-km 65 --date 2025-01-01");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(looksLikeOneJsonObject(r.out)) << r.out;
  EXPECT_NEAR(jsonNumber(r.out, "X_nT"), 24299.852822, 0.1) << r.out;
  EXPECT_NEAR(jsonNumber(r.out, "Y_nT"), 210.517066, 0.1) << r.out;
  EXPECT_NEAR(jsonNumber(r.out, "Z_nT"), 50037.923998, 0.1) << r.out;
  EXPECT_NEAR(jsonNumber(r.out, "H_nT"), 24300.764692, 0.1) << r.out;
  EXPECT_NEAR(jsonNumber(r.out, "F_nT"), 55626.621348, 0.1) << r.out;
  EXPECT_NEAR(jsonNumber(r.out, "incl_deg"), 64.10, 0.01) << r.out;
  EXPECT_NEAR(jsonNumber(r.out, "decl_deg"), 0.50, 0.01) << r.out;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(WmmTool, ExplicitCofFileGivesTheSameField) {
  const auto r = runTool("--lat 43 --lon 93 --alt-km 65 --date 2025-01-01 --cof " +
                         shellQuote(headingd::wmm_test::referenceFile("WMM2025.COF")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(jsonNumber(r.out, "X_nT"), 24299.852822, 0.1) << r.out;
}

TEST(WmmTool, WarnsOutsideValidity) {
  const auto r = runTool("--lat 43 --lon 93 --alt-km 65 --date 2031-03-01");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(looksLikeOneJsonObject(r.out)) << r.out;
  EXPECT_NE(r.out.find("\"warning\":\"date 2031-03-01"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_TRUE(std::isfinite(jsonNumber(r.out, "F_nT"))) << r.out;
}

TEST(WmmTool, BadArgumentsExitWithTwo) {
  for (const std::string args :
       {"--lat 91 --lon 93 --alt-km 65 --date 2025-01-01", "--lat nan --lon 93 --alt-km 65 --date 2025-01-01",
        "--lat north --lon 93 --alt-km 65 --date 2025-01-01", "--lat 43 --lon 400 --alt-km 65 --date 2025-01-01",
        "--lat 43 --lon 93 --alt-km 65 --date 2025-02-29", "--lat 43 --lon 93 --alt-km 65 --date 2025/01/01",
        "--lat 43 --lon 93 --alt-km 65 --date 2025-1-1", "--lat 43 --lon 93 --alt-km 65",
        "--lat 43 --lon 93 --date 2025-01-01 --bogus"}) {
    SCOPED_TRACE(args);
    const auto r = runTool(args);
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(r.err.empty());
  }
  const auto lat = runTool("--lat 91 --lon 93 --alt-km 65 --date 2025-01-01");
  EXPECT_NE(lat.err.find("--lat"), std::string::npos) << lat.err;
  const auto date = runTool("--lat 43 --lon 93 --alt-km 65 --date 2025-02-29");
  EXPECT_NE(date.err.find("--date"), std::string::npos) << date.err;
}

TEST(WmmTool, UnreadableOrMalformedCofExitsWithOne) {
  const auto missing = runTool("--lat 43 --lon 93 --alt-km 65 --date 2025-01-01 --cof /nonexistent/WMM.COF");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("/nonexistent/WMM.COF"), std::string::npos) << missing.err;
  // A real file that is not a COF: the message names the file and line.
  const auto bad = runTool("--lat 43 --lon 93 --alt-km 65 --date 2025-01-01 --cof " +
                           shellQuote(headingd::wmm_test::referenceFile("WMM2025_TEST_VALUES.csv")));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("WMM2025_TEST_VALUES.csv:1:"), std::string::npos) << bad.err;
}

}  // namespace
