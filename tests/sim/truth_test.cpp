// truth.csv and imu.csv as files: headers, row counts, the relations between the columns,
// and the scenario durations.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "headingd/core/angles.hpp"
#include "headingd/core/heading_definition.hpp"
#include "sim_test_support.hpp"

namespace headingd::sim_test {
namespace {

using core::kRadPerDeg;

TEST(Scenarios, DurationsAndRowCounts) {
  const std::map<std::string, double> expected = {
      {"thesis-declination", 244.0},
      {"urban-walk", 600.0},
      {"static-disturbed", 120.0},
      {"crawl", 116.0},
      {"run", 180.0},
      {"calib-six-position", 122.0},
      {"calib-rotation", 4.0},
      {"calib-rotation-long", 60.0},
      {"shake", 100.0},
      {"shake-any", 100.0},
      {"handheld", 100.0},
      {"slow-rotation", 120.0},
      {"indoor-static", 310.0},
      {"moving-disturbances", 210.0},
      {"vehicle-ride", 305.0},
      // The phone scenarios draw their opening rest (1-5 s) before 115 s of walking (running: 110 s).
      {"phone-texting", 115.0},
      {"phone-calling", 115.0},
      {"phone-swinging", 115.0},
      {"phone-pocket", 115.0},
      {"phone-running", 110.0},
      {"phone-running-circles", 110.0}};
  ASSERT_EQ(sim::scenarioNames().size(), expected.size());
  for (const std::string& name : sim::scenarioNames()) {
    const sim::Scenario s = sim::makeScenario(name);
    const bool drawn_rest = name.starts_with("phone-");
    if (drawn_rest) {
      EXPECT_GE(s.durationS(), expected.at(name) + 1.0) << name;
      EXPECT_LE(s.durationS(), expected.at(name) + 5.0) << name;
    } else {
      EXPECT_DOUBLE_EQ(s.durationS(), expected.at(name)) << name;
    }
    EXPECT_FALSE(s.description.empty());
    const sim::SimResult& r = run(config(name, 1, sim::ImuGrade::kConsumer, 20.0));
    EXPECT_EQ(r.imu.size(), static_cast<std::size_t>(s.durationS() * 20.0 + 1e-9) + 1) << name;
    EXPECT_NEAR(r.imu.back().t_s, s.durationS(), drawn_rest ? 0.05 : 1e-12) << name;
    EXPECT_EQ(r.gps.size(), static_cast<std::size_t>(s.durationS()) + 1) << name;
  }
  EXPECT_THROW(sim::makeScenario("no-such-scenario"), std::invalid_argument);
}

TEST(Scenarios, ThesisDeclinationWalksNorthEastSouthWest) {
  const sim::SimResult& r = run(config("thesis-declination", 1, sim::ImuGrade::kConsumer, 20.0));
  const double walk_starts[] = {10.0, 68.0, 126.0, 184.0};
  for (int leg = 0; leg < 4; ++leg) {
    // The middle of each 50 s walk: mean direction of travel.
    double sn = 0.0, se = 0.0;
    for (const auto& s : r.trajectory.states) {
      if (s.t_s > walk_starts[leg] + 5.0 && s.t_s < walk_starts[leg] + 45.0) {
        EXPECT_EQ(s.activity, sim::Activity::kWalking);
        sn += s.velocity_ned_mps.x();
        se += s.velocity_ned_mps.y();
      }
    }
    EXPECT_NEAR(core::wrapAngle(std::atan2(se, sn) - leg * 90.0 * kRadPerDeg), 0.0, 2.0 * kRadPerDeg) << "leg " << leg;
  }
}

TEST(Scenarios, WalkingHasAPersonsCadenceAndSpeed) {
  const sim::SimResult& r = run(config("run", 1, sim::ImuGrade::kIdeal, 100.0));
  // Count vertical-acceleration peaks (zero crossings of a_down going up) over 10 s.
  const auto cadence = [&](double from_s) {
    int crossings = 0;
    double speed = 0.0;
    const auto k0 = static_cast<std::size_t>(from_s * 100.0);
    for (std::size_t k = k0; k < k0 + 1000; ++k) {
      const double a0 = r.trajectory.states[k].accel_ned_mps2.z(), a1 = r.trajectory.states[k + 1].accel_ned_mps2.z();
      if (a0 < 0.0 && a1 >= 0.0) ++crossings;
      speed += std::hypot(r.trajectory.states[k].velocity_ned_mps.x(), r.trajectory.states[k].velocity_ned_mps.y());
    }
    return std::pair{crossings / 10.0, speed / 1000.0};
  };
  const auto [walk_hz, walk_speed] = cadence(15.0);
  EXPECT_NEAR(walk_hz, 1.9, 0.2);
  EXPECT_NEAR(walk_speed, 1.35, 0.15);
  const auto [run_hz, run_speed] = cadence(40.0);
  EXPECT_NEAR(run_hz, 2.8, 0.2);
  EXPECT_NEAR(run_speed, 3.0, 0.2);
}

TEST(TruthCsv, ColumnsAreConsistent) {
  sim::SimConfig c = config("crawl", 2, sim::ImuGrade::kConsumer, 20.0);
  c.decl_anomaly_deg = -1.5;
  c.mount_yaw_deg = 12.0;
  const sim::SimResult& r = run(c);
  const auto lines = splitLines(render(r, sim::writeTruthCsv));
  ASSERT_EQ(lines.size(), r.imu.size() + 1);
  EXPECT_EQ(lines[0], sim::kTruthHeader);
  EXPECT_EQ(lines[0].rfind("t,heading_true_deg,heading_mag_deg,declination_deg,lat_deg,lon_deg", 0), 0u);
  const auto header = splitFields(lines[0]);
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto f = splitFields(lines[k]);
    ASSERT_EQ(f.size(), header.size());
    const double heading_true = std::stod(f[col["heading_true_deg"]]);
    const double heading_mag = std::stod(f[col["heading_mag_deg"]]);
    const double declination = std::stod(f[col["declination_deg"]]);
    EXPECT_NEAR(std::remainder(heading_true - heading_mag - declination, 360.0), 0.0, 2e-6);
    EXPECT_NEAR(declination, r.wmm.declination_deg - 1.5, 1e-6);
    EXPECT_GE(heading_true, 0.0);
    EXPECT_LT(heading_true, 360.0);
    EXPECT_DOUBLE_EQ(std::stod(f[col["mount_yaw_deg"]]), 12.0);
    EXPECT_DOUBLE_EQ(std::stod(f[col["t"]]), r.imu[k - 1].t_s);
    // The body quaternion's heading is the heading column (definition 2.5.1).
    const core::Quat q(std::stod(f[col["body_qw"]]), std::stod(f[col["body_qx"]]), std::stod(f[col["body_qy"]]),
                       std::stod(f[col["body_qz"]]));
    EXPECT_NEAR(std::remainder(core::headingOf(q.normalized()) / kRadPerDeg - heading_true, 360.0), 0.0, 1e-5);
  }
  // The start is the configured place.
  const auto first = splitFields(lines[1]);
  EXPECT_NEAR(std::stod(first[col["lat_deg"]]), 59.33, 1e-9);
  EXPECT_NEAR(std::stod(first[col["lon_deg"]]), 18.07, 1e-9);
}

TEST(TruthCsv, HeadingIsTheBodysNotTheSensors) {
  sim::SimConfig c = config("thesis-declination", 2, sim::ImuGrade::kIdeal, 20.0);
  c.mount_yaw_deg = 45.0;
  const sim::SimResult& r = run(c);
  const auto lines = splitLines(render(r, sim::writeTruthCsv));
  // Walking north (t = 30 s): the body heads ~0°, the sensor ~45°.
  const auto f = splitFields(lines[1 + 30 * 20]);
  EXPECT_LT(std::abs(std::remainder(std::stod(f[1]), 360.0)), 6.0);
  EXPECT_NEAR(std::remainder(core::headingOf(r.imu[30 * 20].q_ns) / kRadPerDeg, 360.0), 45.0, 6.0);
}

TEST(ImuCsv, BroadLayoutWithTheTrueSensorAttitude) {
  const sim::SimResult& r = run(config("crawl", 2, sim::ImuGrade::kConsumer, 20.0));
  const auto lines = splitLines(render(r, sim::writeImuCsv));
  ASSERT_EQ(lines.size(), r.imu.size() + 1);
  EXPECT_EQ(lines[0], "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z,ref_w,ref_x,ref_y,ref_z,moving");
  EXPECT_EQ(lines[1].rfind("0.000000,", 0), 0u);
  bool any_moving = false, any_still = false;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto f = splitFields(lines[k]);
    ASSERT_EQ(f.size(), 15u);
    const core::Quat ref(std::stod(f[10]), std::stod(f[11]), std::stod(f[12]), std::stod(f[13]));
    EXPECT_NEAR(ref.norm(), 1.0, 1e-8);
    EXPECT_LT(ref.angularDistance(r.imu[k - 1].q_ns), 1e-8);
    EXPECT_NEAR(std::stod(f[4]), r.imu[k - 1].accel_m_s2.x(), 1e-7);
    any_moving = any_moving || f[14] == "1";
    any_still = any_still || f[14] == "0";
  }
  EXPECT_TRUE(any_moving);
  EXPECT_TRUE(any_still);
}

TEST(Config, BadValuesAreRefusedByName) {
  sim::SimConfig c;
  c.gps_rate_hz = 3.0;
  EXPECT_THROW(sim::validate(c), std::invalid_argument);
  c = {};
  c.imu_rate_hz = 0.0;
  EXPECT_THROW(sim::validate(c), std::invalid_argument);
  c = {};
  c.month = 2;
  c.day = 30;
  EXPECT_THROW(sim::validate(c), std::invalid_argument);
  c = {};
  c.mount_pitch_deg = 91.0;
  EXPECT_THROW(sim::validate(c), std::invalid_argument);
  c = {};
  c.mount_roll_deg = std::nan("");
  EXPECT_THROW(sim::validate(c), std::invalid_argument);
  c = {};
  EXPECT_NO_THROW(sim::validate(c));
}

}  // namespace
}  // namespace headingd::sim_test
