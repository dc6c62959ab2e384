// EstimatorParams from TOML: defaults, values, and errors that name the file, line and key.
#include "headingd/core/params_toml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace headingd::core {
namespace {

// Every tunable equal in a and b.
void expectSameParams(const EstimatorParams& a, const EstimatorParams& b) {
  for (const ParamSpec& spec : estimatorParamSpecs()) EXPECT_EQ(a.*(spec.member), b.*(spec.member)) << spec.key;
}

// The ConfigError message of parsing `text`, or "" if it parsed.
std::string errorOf(const std::string& text, const std::string& source = "conf/test.toml") {
  try {
    parseEstimatorParams(text, source);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// The message names the source, the line ("source:LINE") and the key.
void expectNamesFileLineKey(const std::string& message, int line, const std::string& key) {
  EXPECT_NE(message, "") << "no ConfigError";
  EXPECT_NE(message.find("conf/test.toml:" + std::to_string(line)), std::string::npos)
      << "message does not name the file and line " << line << ": " << message;
  EXPECT_NE(message.find(key), std::string::npos) << "message does not name the key '" << key << "': " << message;
}

TEST(ParamsToml, EmptyDocumentGivesDefaults) {
  expectSameParams(parseEstimatorParams("", "empty.toml"), EstimatorParams{});
  expectSameParams(parseEstimatorParams("# only a comment\n\n", "comment.toml"), EstimatorParams{});
  expectSameParams(parseEstimatorParams("[estimator]\n", "table.toml"), EstimatorParams{});
}

TEST(ParamsToml, ValidTableSetsValuesAndKeepsTheRest) {
  const EstimatorParams p = parseEstimatorParams(
      "[estimator]\n"
      "gyro_noise_rad_s = 0.01\n"
      "max_sample_gap_s = 1        # an integer converts\n"
      "accel_noise_m_s2 = 0.3\n"
      "disturbance_up_to_walking = 3.5\n"
      "redefine_heading_enter = 0.5\n"
      "mag_heading_time_constant_s = inf\n",
      "ok.toml");
  EXPECT_EQ(p.gyro_noise_rad_s, 0.01);
  EXPECT_EQ(p.max_sample_gap_s, 1.0);
  EXPECT_EQ(p.accel_noise_m_s2, 0.3);
  EXPECT_EQ(p.disturbance_up_to_walking, 3.5);
  EXPECT_EQ(p.redefine_heading_enter, 0.5);
  EXPECT_TRUE(std::isinf(p.mag_heading_time_constant_s));
  const EstimatorParams d;
  EXPECT_EQ(p.gravity_m_s2, d.gravity_m_s2);
  EXPECT_EQ(p.bias_max_rad_s, d.bias_max_rad_s);
  EXPECT_EQ(p.disturbance_up_to_running, d.disturbance_up_to_running);
}

TEST(ParamsToml, EveryKeyCanBeSet) {
  for (const ParamSpec& spec : estimatorParamSpecs()) {
    // A value inside the range near the default (keeps the cross-checks): a little below it,
    // or above it for a default at the minimum.
    const EstimatorParams d;
    const double current = d.*(spec.member);
    const double value = current > spec.min ? current - 0.0025 * (current - spec.min)
                                            : current + 0.0025 * (std::min(spec.max, current + 1.0) - current);
    ASSERT_NE(value, d.*(spec.member)) << spec.key;
    std::ostringstream text;
    text.precision(17);
    text << "[estimator]\n" << spec.key << " = " << value << "\n";
    const EstimatorParams p = parseEstimatorParams(text.str(), "one.toml");
    EXPECT_EQ(p.*(spec.member), value) << spec.key;
  }
}

TEST(ParamsToml, UnknownKeyIsAnError) {
  const std::string m = errorOf("[estimator]\ngyro_noise_rad_s = 0.01\n\ngyro_nosie_rad_s = 0.02\n");
  expectNamesFileLineKey(m, 4, "gyro_nosie_rad_s");
  EXPECT_NE(m.find("unknown key"), std::string::npos) << m;
}

TEST(ParamsToml, UnknownTableIsAnError) {
  expectNamesFileLineKey(errorOf("# typo\n[estimatr]\ngravity_m_s2 = 9.8\n"), 2, "estimatr");
  EXPECT_NE(errorOf("estimator = 5\n").find("conf/test.toml"), std::string::npos);
}

TEST(ParamsToml, WrongTypeIsAnError) {
  const std::string m = errorOf("[estimator]\n\n\ngyro_noise_rad_s = \"fast\"\n");
  expectNamesFileLineKey(m, 4, "gyro_noise_rad_s");
  EXPECT_NE(m.find("expected a number"), std::string::npos) << m;
  expectNamesFileLineKey(errorOf("[estimator]\nbias_max_rad_s = true\n"), 2, "bias_max_rad_s");
  expectNamesFileLineKey(errorOf("[estimator]\nbias_max_rad_s = [0.1]\n"), 2, "bias_max_rad_s");
}

TEST(ParamsToml, OutOfRangeValueIsAnError) {
  const std::string m = errorOf("[estimator]\ngyro_noise_rad_s = 0.01\ngravity_m_s2 = 12.0\n");
  expectNamesFileLineKey(m, 3, "gravity_m_s2");
  EXPECT_NE(m.find("9.7"), std::string::npos) << "message should say what was expected: " << m;
  EXPECT_NE(m.find("9.9"), std::string::npos) << m;
  expectNamesFileLineKey(errorOf("[estimator]\nmax_sample_gap_s = -1\n"), 2, "max_sample_gap_s");
  expectNamesFileLineKey(errorOf("[estimator]\ngyro_noise_rad_s = nan\n"), 2, "gyro_noise_rad_s");
  expectNamesFileLineKey(errorOf("[estimator]\nbackup_reset_period_s = inf\n"), 2, "backup_reset_period_s");
}

TEST(ParamsToml, BadHysteresisOrderIsAnError) {
  // Down threshold above the up threshold: the selector would oscillate.
  const std::string m = errorOf("[estimator]\n# walking\ndisturbance_down_to_standing = 3.0\n");
  expectNamesFileLineKey(m, 3, "disturbance_down_to_standing");
  EXPECT_NE(m.find("hysteresis"), std::string::npos) << m;
  expectNamesFileLineKey(errorOf("[estimator]\nredefine_heading_enter = 0.6\nredefine_heading_leave = 0.5\n"), 3,
                         "redefine_heading_leave");
}

TEST(ParamsToml, RestoreAgeBelowHalfTheBackgroundPeriodIsAnError) {
  // The older background heading is always half a period to a period old: a maximum age
  // under half the period means the restore can never happen.
  const std::string m = errorOf("[estimator]\nbackup_reset_period_s = 10\n\nmag_restore_max_age_s = 3\n");
  expectNamesFileLineKey(m, 4, "mag_restore_max_age_s");
  EXPECT_NE(m.find("backup_reset_period_s"), std::string::npos) << m;
  EXPECT_NE(m.find("never"), std::string::npos) << m;
  // Raising the period past twice the age is the same mistake, named at the period's line.
  expectNamesFileLineKey(errorOf("[estimator]\nmag_restore_max_age_s = 10\nbackup_reset_period_s = 30\n"), 3,
                         "backup_reset_period_s");
  EXPECT_EQ(errorOf("[estimator]\nmag_restore_max_age_s = 0\n"), "") << "0 turns the restore off";
  EXPECT_EQ(errorOf("[estimator]\nmag_restore_max_age_s = 5\n"), "") << "exactly half the default period";
}

TEST(ParamsToml, ValidateEstimatorParamsChecksOrder) {
  EXPECT_NO_THROW(validateEstimatorParams(EstimatorParams{}, "defaults"));
  EstimatorParams p;
  p.disturbance_down_to_walking = 50.0;
  EXPECT_THROW(validateEstimatorParams(p, "x"), ConfigError);
  p = EstimatorParams{};
  p.disturbance_up_to_running = 1.5;  // below the step up to walking
  p.disturbance_down_to_walking = 1.2;
  EXPECT_THROW(validateEstimatorParams(p, "x"), ConfigError);
}

TEST(ParamsToml, SyntaxErrorsNameFileLineAndKey) {
  // toml++'s description says what was wrong; the message adds where (file, line) and, when
  // the broken line is a key/value pair, which key.
  const std::string missing_value = errorOf("[estimator]\n\ngyro_noise_rad_s = \n");
  expectNamesFileLineKey(missing_value, 3, "gyro_noise_rad_s");
  EXPECT_NE(missing_value.find("syntax error"), std::string::npos) << missing_value;
  expectNamesFileLineKey(errorOf("[estimator]\ngyro_noise_rad_s = 0.0.1\n"), 2, "gyro_noise_rad_s");
  expectNamesFileLineKey(errorOf("[estimator]\ngyro_noise_rad_s = 0.01\ngyro_noise_rad_s = 0.02\n"), 3,
                         "gyro_noise_rad_s");
  // An unclosed table header has no key: file and line.
  const std::string unclosed = errorOf("[estimator\ngyro_noise_rad_s = 0.01\n");
  expectNamesFileLineKey(unclosed, 1, "syntax error");
}

TEST(ParamsToml, EveryParamSpecHasADefaultInRange) {
  const EstimatorParams d;
  std::set<std::string> keys;
  std::vector<double EstimatorParams::*> members;
  for (const ParamSpec& spec : estimatorParamSpecs()) {
    const double value = d.*(spec.member);
    EXPECT_GE(value, spec.min) << spec.key;
    EXPECT_LE(value, spec.max) << spec.key;
    EXPECT_LT(spec.min, spec.max) << spec.key;
    EXPECT_NE(std::string(spec.unit), "") << spec.key;
    EXPECT_TRUE(keys.insert(spec.key).second) << "duplicate key " << spec.key;
    EXPECT_EQ(std::count(members.begin(), members.end(), spec.member), 0) << "two keys for one member: " << spec.key;
    members.push_back(spec.member);
  }
  // Every member of EstimatorParams (all doubles) has its spec.
  EXPECT_EQ(estimatorParamSpecs().size(), sizeof(EstimatorParams) / sizeof(double));
}

TEST(ParamsToml, ShippedConfigListsEveryKeyWithItsDefault) {
  std::ifstream in(HEADINGD_ESTIMATOR_TOML);
  ASSERT_TRUE(in) << HEADINGD_ESTIMATOR_TOML;
  std::stringstream text;
  text << in.rdbuf();
  expectSameParams(parseEstimatorParams(text.str(), HEADINGD_ESTIMATOR_TOML), EstimatorParams{});
  for (const ParamSpec& spec : estimatorParamSpecs()) {
    EXPECT_NE(text.str().find(std::string("\n") + spec.key + " = "), std::string::npos) << spec.key;
  }
}

}  // namespace
}  // namespace headingd::core
