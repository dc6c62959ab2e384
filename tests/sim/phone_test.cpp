// The phone grade and the phone scenarios (issue 28): the grade's drawn values lie in their
// ranges, the magnetometer is held between its samples at the drawn rate, it and the
// accelerometer lag the gyro by the drawn lags, the true gyro bias is exposed, and each carry
// mode moves the phone as its comment says; every phone scenario starts with a short rest of
// zero true rate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <numbers>
#include <set>
#include <string>

#include "headingd/core/angles.hpp"
#include "headingd/sim/imu_model.hpp"
#include "headingd/sim/phone_imu.hpp"
#include "headingd/sim/phone_scenarios.hpp"
#include "sim_test_support.hpp"

namespace headingd::sim_test {
namespace {

using core::kRadPerDeg;
using core::Quat;
using core::Vec3;

bool within(double x, const sim::DrawRange& r) { return x >= r.lo && x <= r.hi; }

// Elevation of a sensor axis above the horizontal (NED: up is -z).
double elevationDeg(const Quat& q_ns, const Vec3& axis) { return std::asin(-(q_ns * axis).z()) / kRadPerDeg; }

TEST(PhoneGrade, DrawnValuesLieInTheirRangesAndSpanThem) {
  using R = sim::PhoneRanges;
  double lowest_noise = 1.0, highest_noise = 0.0, lowest_lag = 1.0, highest_lag = 0.0, largest_bias = 0.0;
  std::map<double, int> full_scales;
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    const sim::ImuModel m = sim::imuModel(sim::ImuGrade::kPhone, 51.9, sim::Rng(seed));
    const double gyro_noise_100hz = m.errors.gyro.noise_density.x() * std::sqrt(100.0);
    EXPECT_TRUE(within(gyro_noise_100hz, R::kGyroNoiseAt100Hz_rad_s)) << seed << ": " << gyro_noise_100hz;
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(within(std::abs(m.errors.gyro.offset_drawn(i)), R::kGyroBiasMagnitude_rad_s)) << seed;
      largest_bias = std::max(largest_bias, std::abs(m.errors.gyro.offset_drawn(i)));
    }
    EXPECT_TRUE(m.errors.gyro.offset_half_width.isZero());
    EXPECT_TRUE(within(m.errors.accel.noise_density.x(), R::kAccelNoiseDensity)) << seed;
    EXPECT_TRUE(within(m.errors.mag.noise_sigma.x(), R::kMagNoise_uT)) << seed;
    EXPECT_TRUE(within(m.timing.mag_rate_hz, R::kMagRate_hz)) << seed;
    EXPECT_TRUE(within(m.timing.mag_lag_s, R::kMagLag_s)) << seed;
    EXPECT_TRUE(within(m.timing.accel_lag_s, R::kAccelLag_s)) << seed;
    ++full_scales[m.errors.accel.full_scale];
    EXPECT_GE(m.timing.mag_first_sample_s, 0.0);
    EXPECT_LT(m.timing.mag_first_sample_s, 1.0 / m.timing.mag_rate_hz);
    lowest_noise = std::min(lowest_noise, gyro_noise_100hz);
    highest_noise = std::max(highest_noise, gyro_noise_100hz);
    lowest_lag = std::min(lowest_lag, m.timing.mag_lag_s);
    highest_lag = std::max(highest_lag, m.timing.mag_lag_s);
  }
  // Ranges, not one sensor: the draws reach near both ends.
  EXPECT_LT(lowest_noise, 0.0035);
  EXPECT_GT(highest_noise, 0.018);
  EXPECT_LT(lowest_lag, 0.021);
  EXPECT_GT(highest_lag, 0.039);
  EXPECT_GT(largest_bias, 5.0 * kRadPerDeg);
  // The accelerometer's full scale is one of the listed ones, each drawn about as often.
  ASSERT_EQ(full_scales.size(), std::size(R::kAccelFullScale_m_s2));
  for (const double fs : R::kAccelFullScale_m_s2) EXPECT_GT(full_scales[fs], 70) << fs;
}

TEST(PhoneGrade, GyroNoiseIsADensity) {
  // The same seed draws the same phone at any rate: per-sample sigma scales with sqrt(rate).
  const sim::SimResult& at100 = run(config("phone-texting", 5, sim::ImuGrade::kPhone, 100.0));
  const sim::SimResult& at50 = run(config("phone-texting", 5, sim::ImuGrade::kPhone, 50.0));
  EXPECT_TRUE(within(at100.gyro.white_sigma.x(), sim::PhoneRanges::kGyroNoiseAt100Hz_rad_s));
  EXPECT_NEAR(at50.gyro.white_sigma.x(), at100.gyro.white_sigma.x() / std::sqrt(2.0), 1e-12);
  EXPECT_EQ(at50.timing.mag_rate_hz, at100.timing.mag_rate_hz);
}

TEST(PhoneGrade, IsNamedAndOtherGradesKeepTheirTiming) {
  EXPECT_EQ(sim::parseImuGrade("phone"), sim::ImuGrade::kPhone);
  EXPECT_STREQ(sim::imuGradeName(sim::ImuGrade::kPhone), "phone");
  try {
    (void)sim::parseImuGrade("fone");
    FAIL() << "an unknown grade must throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("phone"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)sim::imuErrorParams(sim::ImuGrade::kPhone, 50.0), std::invalid_argument);
  const sim::SimResult& r = run(config("phone-pocket", 2, sim::ImuGrade::kConsumer));
  EXPECT_TRUE(r.timing.isDefault());
  for (const sim::ImuRow& row : r.imu) ASSERT_EQ(row.mag_truth_t_s, row.t_s);
}

TEST(PhoneMagnetometer, IsHeldBetweenSamplesAtTheDrawnRate) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const sim::SimResult& r = run(config("phone-swinging", seed, sim::ImuGrade::kPhone));
    const sim::SensorTiming& t = r.timing;
    std::size_t samples = 1;
    for (std::size_t k = 1; k < r.imu.size(); ++k) {
      const sim::ImuRow& a = r.imu[k - 1];
      const sim::ImuRow& b = r.imu[k];
      if (b.mag_truth_t_s == a.mag_truth_t_s) {
        ASSERT_EQ(b.mag_uT, a.mag_uT) << "seed " << seed << " row " << k << ": a held sample is repeated as it is";
        continue;
      }
      ++samples;
      EXPECT_NE(b.mag_uT, a.mag_uT);
      // A new sample is the magnetometer's latest at this row: taken within the last period.
      const double taken = b.mag_truth_t_s + t.mag_lag_s;
      EXPECT_LE(taken, b.t_s + 1e-9);
      EXPECT_GT(taken, b.t_s - 1.0 / t.mag_rate_hz - 1e-9);
      EXPECT_NEAR(std::remainder(taken - t.mag_first_sample_s, 1.0 / t.mag_rate_hz), 0.0, 1e-9);
    }
    const double duration = r.imu.back().t_s - r.imu.front().t_s;
    // Row 0 holds the sample before it (j = -1), so one more than rate x duration, give or take one.
    EXPECT_NEAR(static_cast<double>(samples) / duration, t.mag_rate_hz, 2.5 / duration) << "seed " << seed;
  }
}

// The true magnetometer vector at any time, interpolated between rows (q_ns slerped, the field
// linear), as the test sees it.
Vec3 trueMagAt(const sim::SimResult& r, double t_s) {
  const double x = std::clamp(t_s * r.config.imu_rate_hz, 0.0, static_cast<double>(r.imu.size() - 2));
  const auto i = static_cast<std::size_t>(x);
  const double w = x - static_cast<double>(i);
  const Quat q = r.imu[i].q_ns.slerp(w, r.imu[i + 1].q_ns);
  return q.conjugate() * ((1.0 - w) * r.field_ned_uT[i] + w * r.field_ned_uT[i + 1]);
}

TEST(PhoneMagnetometer, LagsTheGyroByTheDrawnLag) {
  // Undo the drawn distortion and offset, then find the delay behind each sample's own time
  // that fits the readings best: it is the drawn lag.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const sim::SimResult& r = run(config("phone-swinging", seed, sim::ImuGrade::kPhone));
    const core::Mat3 d_inverse = r.mag.distortion.inverse();
    double best_lag = -1.0, best_cost = 1e300;
    for (int lag_ms = 0; lag_ms <= 60; ++lag_ms) {
      double cost = 0.0;
      for (std::size_t k = 1; k < r.imu.size(); ++k) {
        if (r.imu[k].mag_truth_t_s == r.imu[k - 1].mag_truth_t_s) continue;  // one term per sample
        const double taken = r.imu[k].mag_truth_t_s + r.timing.mag_lag_s;
        const Vec3 seen = d_inverse * (r.imu[k].mag_uT - r.mag.offset);
        cost += (seen - trueMagAt(r, taken - 1e-3 * lag_ms)).squaredNorm();
      }
      if (cost < best_cost) best_cost = cost, best_lag = 1e-3 * lag_ms;
    }
    EXPECT_NEAR(best_lag, r.timing.mag_lag_s, 0.0015) << "seed " << seed;
  }
}

TEST(PhoneAccelerometer, LagsTheGyroByTheDrawnLag) {
  // The interval-mean specific force of each row from the true motion, shifted by candidate
  // lags (linear between rows): the drawn lag fits the readings best.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const sim::SimResult& r = run(config("phone-swinging", seed, sim::ImuGrade::kPhone));
    const auto& states = r.trajectory.states;
    std::vector<Vec3> mean(states.size());
    Vec3 previous = Vec3::Zero();
    for (std::size_t k = 0; k < states.size(); ++k) {
      const Vec3 point = r.imu[k].q_ns.conjugate() * (states[k].accel_ned_mps2 - Vec3(0.0, 0.0, sim::kGravity_m_s2));
      mean[k] = k == 0 ? point : Vec3(0.5 * (previous + point));
      previous = point;
    }
    const core::Mat3 d_inverse = r.accel.distortion.inverse();
    const double rate = r.config.imu_rate_hz;
    double best_lag = -1.0, best_cost = 1e300;
    for (int lag_tenths_ms = 0; lag_tenths_ms <= 80; lag_tenths_ms += 2) {
      const double lag = 1e-4 * lag_tenths_ms;
      double cost = 0.0;
      for (std::size_t k = 10; k < r.imu.size(); ++k) {
        const double x = (r.imu[k].t_s - lag) * rate;
        const auto i = static_cast<std::size_t>(x);
        const double w = x - static_cast<double>(i);
        const Vec3 expected = (1.0 - w) * mean[i] + w * mean[std::min(i + 1, mean.size() - 1)];
        cost += (d_inverse * (r.imu[k].accel_m_s2 - r.accel.offset) - expected).squaredNorm();
      }
      if (cost < best_cost) best_cost = cost, best_lag = lag;
    }
    EXPECT_NEAR(best_lag, r.timing.accel_lag_s, 0.0003) << "seed " << seed;
  }
}

TEST(PhoneAccelerometer, ReadsAtMostItsFullScaleAndClipsWhileRunningAtTwoG) {
  // A ±2 g phone in a runner's hand or pocket reads its limit in a good share of the rows
  // (the shared recordings' Nexus 5 and iPhone 4S: 10-27 % on one axis); a ±8 g one never.
  int two_g_runs = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const sim::SimResult& r = run(config("phone-running", seed, sim::ImuGrade::kPhone));
    const double full_scale = r.accel.full_scale;
    ASSERT_GT(full_scale, 0.0) << seed;
    std::size_t at_limit = 0;
    for (const auto& row : r.imu) {
      EXPECT_LE(row.accel_m_s2.cwiseAbs().maxCoeff(), full_scale) << seed;
      at_limit += row.accel_m_s2.cwiseAbs().maxCoeff() == full_scale;
    }
    const double share = static_cast<double>(at_limit) / static_cast<double>(r.imu.size());
    if (full_scale < 2.5 * sim::kGravity_m_s2) {
      ++two_g_runs;
      EXPECT_GT(share, 0.05) << "seed " << seed;
    } else if (full_scale > 6.0 * sim::kGravity_m_s2) {
      EXPECT_EQ(at_limit, 0u) << "seed " << seed;
    }
  }
  EXPECT_GE(two_g_runs, 1);
}

TEST(PhoneGyro, TrueBiasIsExposedPerRowAndInTruthCsv) {
  const sim::SimResult& r = run(config("phone-texting", 7, sim::ImuGrade::kPhone));
  // At rest the gyro reads its bias plus white noise.
  const double rest_s = r.scenario.phases.front().duration_s;
  Vec3 sum = Vec3::Zero();
  std::size_t n = 0;
  for (const sim::ImuRow& row : r.imu) {
    if (row.t_s >= rest_s) break;
    sum += row.gyro_rad_s - row.gyro_bias_rad_s;
    ++n;
  }
  ASSERT_GT(n, 50u);
  const Vec3 mean = sum / static_cast<double>(n);
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(mean(i)), 4.0 * r.gyro.white_sigma(i) / std::sqrt(n)) << i;
  // The bias is the drawn offset plus a drifting part of the consumer grade's size.
  EXPECT_LT((r.imu.front().gyro_bias_rad_s - r.gyro.offset).norm(), 0.01);
  EXPECT_NE(r.imu.front().gyro_bias_rad_s, r.imu.back().gyro_bias_rad_s);
  // truth.csv carries the same numbers.
  const auto lines = splitLines(render(r, sim::writeTruthCsv));
  const auto header = splitFields(lines[0]);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  for (const std::size_t k : {std::size_t{0}, r.imu.size() / 2, r.imu.size() - 1}) {
    const auto f = splitFields(lines[k + 1]);
    const Vec3 b(std::stod(f[column("gyro_bias_x")]), std::stod(f[column("gyro_bias_y")]),
                 std::stod(f[column("gyro_bias_z")]));
    EXPECT_LT((b - r.imu[k].gyro_bias_rad_s).norm(), 1e-8) << k;
  }
}

TEST(PhoneScenarios, StartWithAShortRestOfZeroTrueRate) {
  for (const std::string& name : sim::phoneScenarioNames()) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const sim::SimResult& r = run(config(name, seed, sim::ImuGrade::kIdeal));
      const double rest_s = r.scenario.phases.front().duration_s;
      EXPECT_GE(rest_s, 1.0);
      EXPECT_LE(rest_s, 5.0);
      std::size_t rest_rows = 0;
      for (const sim::ImuRow& row : r.imu) {
        if (row.t_s > rest_s) break;
        ASSERT_LT(row.gyro_rad_s.norm(), 1e-12) << name << " seed " << seed << " t " << row.t_s;
        ASSERT_FALSE(row.moving);
        ++rest_rows;
      }
      EXPECT_GE(rest_rows, 100u);
      EXPECT_TRUE(r.imu.back().t_s > 100.0) << name;
      EXPECT_TRUE(r.trajectory.states[r.imu.size() / 2].indoor) << name;
    }
  }
}

// Rows of the walk (moving, past the first seconds).
template <typename F>
void forWalkingRows(const sim::SimResult& r, F f) {
  const double start = r.scenario.phases.front().duration_s + 3.0;
  for (std::size_t k = 0; k < r.imu.size(); ++k) {
    if (r.imu[k].t_s > start && r.imu[k].moving) f(k, r.imu[k]);
  }
}

// Peak-to-peak of a per-row quantity in consecutive 2-s windows of the walk (two strides).
template <typename F>
std::vector<double> peakToPeakPerWindow(const sim::SimResult& r, F value) {
  std::vector<double> out;
  const auto window = static_cast<std::size_t>(2.0 * r.config.imu_rate_hz);
  std::vector<double> v;
  forWalkingRows(r, [&](std::size_t, const sim::ImuRow& row) { v.push_back(value(row)); });
  for (std::size_t i = 0; i + window <= v.size(); i += window) {
    const auto [lo, hi] =
        std::minmax_element(v.begin() + static_cast<long>(i), v.begin() + static_cast<long>(i + window));
    out.push_back(*hi - *lo);
  }
  return out;
}

TEST(PhoneCarry, TextingHoldsTheScreenUpAndTiltedWithinTheRange) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const sim::SimResult& r = run(config("phone-texting", seed, sim::ImuGrade::kIdeal));
    ASSERT_EQ(r.scenario.carry->mode, "texting");
    forWalkingRows(r, [&](std::size_t k, const sim::ImuRow& row) {
      // Screen up: the back of the phone (sensor z) points down; its top raised 20-45 deg
      // (give or take the forward lean of walking and the stride's bob).
      ASSERT_GT(elevationDeg(row.q_ns, -Vec3::UnitZ()), 35.0) << "seed " << seed << " row " << k;
      const double tilt = elevationDeg(row.q_ns, Vec3::UnitX());
      ASSERT_GT(tilt, 20.0 - 10.0) << "seed " << seed << " row " << k;
      ASSERT_LT(tilt, 45.0 + 5.0) << "seed " << seed << " row " << k;
    });
  }
}

TEST(PhoneCarry, CallingHoldsThePhoneNearVertical) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const sim::SimResult& r = run(config("phone-calling", seed, sim::ImuGrade::kIdeal));
    ASSERT_EQ(r.scenario.carry->mode, "calling");
    forWalkingRows(r, [&](std::size_t k, const sim::ImuRow& row) {
      ASSERT_GT(elevationDeg(row.q_ns, Vec3::UnitX()), 50.0) << "seed " << seed << " row " << k;
      ASSERT_LT(std::abs(elevationDeg(row.q_ns, Vec3::UnitZ())), 15.0) << "the screen faces the head, sideways";
    });
  }
}

TEST(PhoneCarry, SwingingIsAPendulumOfThirtyToSixtyDegrees) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const sim::SimResult& r = run(config("phone-swinging", seed, sim::ImuGrade::kIdeal));
    const double amplitude = r.scenario.carry->walk_amplitude_deg;
    EXPECT_GE(amplitude, 30.0);
    EXPECT_LE(amplitude, 60.0);
    // The phone's top (forward in the hand) rises and falls with the arm.
    for (const double p2p :
         peakToPeakPerWindow(r, [](const sim::ImuRow& row) { return elevationDeg(row.q_ns, Vec3::UnitX()); })) {
      EXPECT_GT(p2p, 2.0 * amplitude - 8.0) << "seed " << seed;
      EXPECT_LT(p2p, 2.0 * amplitude + 8.0) << "seed " << seed;
    }
  }
}

TEST(PhoneCarry, PocketTurnsWithTheThighAndDrawsEveryPlacement) {
  std::set<std::string> modes;
  for (std::uint64_t seed = 1; seed <= 24; ++seed) {
    const sim::SimResult& r = run(config("phone-pocket", seed, sim::ImuGrade::kIdeal));
    modes.insert(r.scenario.carry->mode);
    if (seed > 6) continue;
    // The phone lies along the thigh: its top is near vertical (up or down), its pitch swings
    // with the thigh through every stride, +-20 deg about 10 deg forward.
    const double upright = r.scenario.carry->mode.ends_with("-upright") ? 1.0 : -1.0;
    forWalkingRows(r, [&](std::size_t k, const sim::ImuRow& row) {
      ASSERT_GT(upright * elevationDeg(row.q_ns, Vec3::UnitX()), 90.0 - 40.0) << "seed " << seed << " row " << k;
    });
    for (const double p2p :
         peakToPeakPerWindow(r, [](const sim::ImuRow& row) { return elevationDeg(row.q_ns, Vec3::UnitX()); })) {
      EXPECT_GT(p2p, 12.0) << "seed " << seed;  // elevation near 90 deg compresses the swing
    }
    for (const double p2p : peakToPeakPerWindow(r, [](const sim::ImuRow& row) {
           // The thigh's angle: the phone's top against down, in the sagittal swing.
           return std::acos(std::clamp(std::abs((row.q_ns * Vec3::UnitX()).z()), 0.0, 1.0)) / kRadPerDeg;
         })) {
      EXPECT_GT(p2p, 12.0) << "seed " << seed;
      EXPECT_LT(p2p, 50.0) << "seed " << seed;
    }
  }
  for (const char* m :
       {"pocket-front-upright", "pocket-front-upside-down", "pocket-back-upright", "pocket-back-upside-down"}) {
    EXPECT_TRUE(modes.contains(m)) << m;
  }
}

TEST(PhoneCarry, RunningCarriesInTheHandOrAPocketAndTurnsFaster) {
  std::set<std::string> modes;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const sim::SimResult& r = run(config("phone-running", seed, sim::ImuGrade::kIdeal));
    const std::string mode = r.scenario.carry->mode;
    modes.insert(mode == "running-hand" ? mode : "pocket");
    // Running swings the limb further and faster than walking: the 95th percentile of the rate
    // in the first walk (phase 1) and in the run (phase 2), each past its first 3 s.
    std::vector<double> walk_rates, run_rates;
    double phase_start = 0.0;
    for (std::size_t p = 0; p < 3; ++p) {
      for (std::size_t k = 0; k < r.imu.size(); ++k) {
        if (r.trajectory.states[k].phase != p || r.imu[k].t_s < phase_start + 3.0) continue;
        (p == 1 ? walk_rates : run_rates).push_back(r.imu[k].gyro_rad_s.norm());
      }
      phase_start += r.scenario.phases[p].duration_s;
      if (p == 0) run_rates.clear();
    }
    const auto percentile95 = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() * 95 / 100];
    };
    const double walk_peak = percentile95(walk_rates), run_peak = percentile95(run_rates);
    EXPECT_GT(run_peak, 1.5 * walk_peak) << "seed " << seed << " " << mode;
    EXPECT_LT(run_peak, 15.0) << "seed " << seed << " " << mode;
  }
  EXPECT_TRUE(modes.contains("running-hand"));
  EXPECT_TRUE(modes.contains("pocket"));
}

TEST(PhoneScenarios, TheRoomsFieldVariesByAFewDegrees) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const sim::SimResult& r = run(config("phone-texting", seed, sim::ImuGrade::kIdeal));
    double sum = 0.0, sum2 = 0.0, lo = 1e9, hi = -1e9;
    std::size_t n = 0;
    const double earth = std::atan2(r.field_ned_uT.front().y() - r.disturbance_ned_uT.front().y(),
                                    r.field_ned_uT.front().x() - r.disturbance_ned_uT.front().x());
    for (const Vec3& f : r.field_ned_uT) {
      const double d = std::remainder(std::atan2(f.y(), f.x()) - earth, 2.0 * std::numbers::pi) / kRadPerDeg;
      sum += d, sum2 += d * d, ++n;
      lo = std::min(lo, d), hi = std::max(hi, d);
    }
    const double rms = std::sqrt(sum2 / static_cast<double>(n));
    EXPECT_GT(rms, 0.7) << "seed " << seed;
    EXPECT_LT(rms, 6.0) << "seed " << seed;
    EXPECT_GT(hi - lo, 3.0) << "seed " << seed;
    EXPECT_LT(hi - lo, 25.0) << "seed " << seed;
  }
}

}  // namespace
}  // namespace headingd::sim_test
