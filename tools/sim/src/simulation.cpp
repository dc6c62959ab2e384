#include "headingd/sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "headingd/core/angles.hpp"
#include "headingd/sim/field_model.hpp"
#include "headingd/sim/trajectory_generator.hpp"

namespace headingd::sim {

namespace {

using core::kRadPerDeg;
using core::Quat;
using core::Vec3;

// Stream ids of Rng::stream: one per part of the model, so that they stay independent.
enum Stream : std::uint64_t { kTrajectory = 1, kField, kGyro, kAccel, kMag, kGps, kImuDraw };

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// Sensor to body: zyx Euler angles of the mount. Without pitch and roll it is the yaw turn
// alone, bit for bit (the runs made before they existed stay the same).
Quat mountRotation(const SimConfig& c) {
  Quat q_bs = core::headingRotation(c.mount_yaw_deg * kRadPerDeg);
  if (c.mount_pitch_deg != 0.0 || c.mount_roll_deg != 0.0) {
    q_bs = (q_bs * Quat(Eigen::AngleAxisd(c.mount_pitch_deg * kRadPerDeg, Vec3::UnitY())) *
            Quat(Eigen::AngleAxisd(c.mount_roll_deg * kRadPerDeg, Vec3::UnitX())))
               .normalized();
  }
  return q_bs;
}

}  // namespace

const char* vectorSamplingName(VectorSampling v) { return v == VectorSampling::kIntervalMean ? "interval" : "point"; }

VectorSampling parseVectorSampling(std::string_view name) {
  if (name == "interval") return VectorSampling::kIntervalMean;
  if (name == "point") return VectorSampling::kPoint;
  throw std::invalid_argument("unknown vector sampling '" + std::string(name) + "' (interval, point)");
}

SimConfig simConfig(std::string scenario, std::uint64_t seed, ImuGrade grade, double imu_rate_hz) {
  SimConfig c;
  c.scenario = std::move(scenario);
  c.seed = seed;
  c.imu_grade = grade;
  c.imu_rate_hz = imu_rate_hz;
  return c;
}

core::ImuSample imuSample(const ImuRow& row) {
  core::ImuSample s;
  s.t_ns = static_cast<std::int64_t>(std::llround(row.t_s * 1e9));
  s.gyro_rad_s = row.gyro_rad_s;
  s.accel_m_s2 = row.accel_m_s2;
  s.mag_uT = row.mag_uT;
  return s;
}

void validate(const SimConfig& c) {
  require(std::isfinite(c.origin.latitude_deg) && std::abs(c.origin.latitude_deg) <= 89.0,
          "--lat must be within -89..89 degrees");
  require(std::isfinite(c.origin.longitude_deg) && std::abs(c.origin.longitude_deg) <= 180.0,
          "--lon must be within -180..180 degrees");
  require(std::isfinite(c.decl_anomaly_deg) && std::abs(c.decl_anomaly_deg) <= 180.0,
          "--decl-anomaly-deg must be within -180..180");
  require(std::isfinite(c.mount_yaw_deg) && std::abs(c.mount_yaw_deg) <= 360.0,
          "--mount-yaw-deg must be within -360..360");
  require(std::isfinite(c.mount_pitch_deg) && std::abs(c.mount_pitch_deg) <= 90.0,
          "--mount-pitch-deg must be within -90..90");
  require(std::isfinite(c.mount_roll_deg) && std::abs(c.mount_roll_deg) <= 180.0,
          "--mount-roll-deg must be within -180..180");
  require(std::isfinite(c.imu_rate_hz) && c.imu_rate_hz >= 10.0 && c.imu_rate_hz <= 1000.0,
          "--rate-hz must be within 10..1000");
  // UTC is written to 0.01 s: only rates whose period is a whole number of hundredths.
  const double g = c.gps_rate_hz;
  require(g == 1.0 || g == 2.0 || g == 4.0 || g == 5.0 || g == 10.0, "--gps-rate-hz must be 1, 2, 4, 5 or 10");
  require(!c.accel_lag_s || (std::isfinite(*c.accel_lag_s) && *c.accel_lag_s >= 0.0 && *c.accel_lag_s <= 0.2),
          "--accel-lag-s must be within 0..0.2");
  require(c.talker == "GP" || c.talker == "GN", "talker must be GP or GN");
  (void)core::decimalYear(c.year, c.month, c.day);  // throws for a date that does not exist
}

SimResult simulate(const SimConfig& config, const core::WorldMagneticModel& wmm) {
  return simulate(config, makeScenario(config.scenario, config.seed), wmm);
}

SimResult simulate(const SimConfig& config, const Scenario& scenario, const core::WorldMagneticModel& wmm) {
  validate(config);
  SimResult r;
  r.config = config;
  r.scenario = scenario;
  r.wmm = wmm.field({config.origin.latitude_deg, config.origin.longitude_deg, config.origin.height_m / 1000.0},
                    core::decimalYear(config.year, config.month, config.day));
  r.wmm_model_name = wmm.modelName();
  const FieldModel field(r.scenario, r.wmm, config.decl_anomaly_deg, Rng::stream(config.seed, kField));
  r.declination_deg = field.declinationDeg();
  r.q_bs = mountRotation(config);
  r.trajectory = generateTrajectory(r.scenario, config.imu_rate_hz, Rng::stream(config.seed, kTrajectory));

  ImuModel model = imuModel(config.imu_grade, field.earthFieldNed_uT().norm(), Rng::stream(config.seed, kImuDraw));
  if (config.accel_lag_s) model.timing.accel_lag_s = *config.accel_lag_s;
  r.timing = model.timing;
  const SensorTiming& timing = model.timing;
  const bool slow_mag = timing.mag_rate_hz > 0.0;
  TriadSensor gyro(model.errors.gyro, config.imu_rate_hz, Rng::stream(config.seed, kGyro));
  TriadSensor accel(model.errors.accel, config.imu_rate_hz, Rng::stream(config.seed, kAccel));
  TriadSensor mag(model.errors.mag, slow_mag ? timing.mag_rate_hz : config.imu_rate_hz, Rng::stream(config.seed, kMag));
  r.gyro = {gyro.distortion(), gyro.offset(), gyro.whiteSigma(), gyro.fullScale()};
  r.accel = {accel.distortion(), accel.offset(), accel.whiteSigma(), accel.fullScale()};
  r.mag = {mag.distortion(), mag.offset(), mag.whiteSigma(), mag.fullScale()};

  // First the true signals of every row, then the sensors read them (a late sensor reads an
  // earlier row's).
  const double dt = 1.0 / config.imu_rate_hz;
  const Vec3 gravity_ned(0.0, 0.0, kGravity_m_s2);
  const auto& states = r.trajectory.states;
  const std::size_t rows = states.size();
  std::vector<Quat> q_ns(rows);
  std::vector<Vec3> gyro_true(rows), accel_true(rows), mag_true(rows);
  r.field_ned_uT.reserve(rows);
  r.disturbance_ned_uT.reserve(rows);
  Quat q_ns_previous = (r.trajectory.q_nb_before_start * r.trajectory.q_b_sensor_before_start * r.q_bs).normalized();
  Vec3 accel_previous = Vec3::Zero(), mag_previous = Vec3::Zero();  // point values at t_{k-1}
  for (std::size_t k = 0; k < rows; ++k) {
    const TruthState& s = states[k];
    q_ns[k] = (s.q_nb * s.q_b_sensor * r.q_bs).normalized();
    const Vec3 disturbance = field.disturbanceNed_uT(s.t_s, s.position_ned_m);
    const Vec3 field_ned = field.earthFieldNed_uT() + disturbance;
    // Row k's rate covers (t_{k-1}, t_k]: q_k = q_{k-1} ⊗ exp(½ ω_k Δt), the way the
    // estimator integrates a sample over the interval that ends at it.
    gyro_true[k] = rateBetween(q_ns_previous, q_ns[k], dt);
    const Vec3 accel_point = q_ns[k].conjugate() * (s.accel_ned_mps2 - gravity_ned);  // f_s = R_nsᵀ (a_n - g_n)
    const Vec3 mag_point = q_ns[k].conjugate() * field_ned;
    // An interval-mean sensor reports the mean over (t_{k-1}, t_k] (trapezoid rule, in its own
    // turning axes); the first row has no interval before it.
    const bool mean = config.vector_sampling == VectorSampling::kIntervalMean && k > 0;
    accel_true[k] = mean ? Vec3(0.5 * (accel_previous + accel_point)) : accel_point;
    mag_true[k] = mean ? Vec3(0.5 * (mag_previous + mag_point)) : mag_point;
    accel_previous = accel_point;
    mag_previous = mag_point;
    r.field_ned_uT.push_back(field_ned);
    r.disturbance_ned_uT.push_back(disturbance);
    q_ns_previous = q_ns[k];
  }

  // Where a time falls between rows (clamped to the run): the row before it and how far on.
  const auto between = [&](double t_s) {
    const double x = std::clamp(t_s * config.imu_rate_hz, 0.0, static_cast<double>(rows - 1));
    const auto i = std::min(static_cast<std::size_t>(x), rows - 1);
    return std::pair{i, i + 1 < rows ? x - static_cast<double>(i) : 0.0};
  };
  const auto accelAt = [&](double t_s) {
    const auto [i, w] = between(t_s);
    return w == 0.0 ? accel_true[i] : Vec3((1.0 - w) * accel_true[i] + w * accel_true[i + 1]);
  };
  // A slower magnetometer samples the field at an instant (its own sampling takes a few ms):
  // the attitude and the field at t_s interpolated between rows.
  const auto magPointAt = [&](double t_s) {
    const auto [i, w] = between(t_s);
    if (w == 0.0) return Vec3(q_ns[i].conjugate() * r.field_ned_uT[i]);
    const Quat q = q_ns[i].slerp(w, q_ns[i + 1]).normalized();
    return Vec3(q.conjugate() * ((1.0 - w) * r.field_ned_uT[i] + w * r.field_ned_uT[i + 1]));
  };

  r.imu.reserve(rows);
  long long last_mag_sample = std::numeric_limits<long long>::min();
  Vec3 mag_reading = Vec3::Zero();
  double mag_truth_t = 0.0;
  for (std::size_t k = 0; k < rows; ++k) {
    const TruthState& s = states[k];
    ImuRow row;
    row.t_s = s.t_s;
    row.gyro_bias_rad_s = gyro.offset() + gyro.driftingBias();  // what measure() adds in this row
    row.gyro_rad_s = gyro.measure(gyro_true[k]);
    row.accel_m_s2 = accel.measure(timing.accel_lag_s > 0.0 ? accelAt(s.t_s - timing.accel_lag_s) : accel_true[k]);
    if (timing.isDefault()) {
      row.mag_uT = mag.measure(mag_true[k]);
      row.mag_truth_t_s = s.t_s;
    } else {
      // The magnetometer's last sample at or before t_k (sample j at first + j / rate, its
      // own clock), describing the field as it was lag before it; repeated until the next.
      const double period = slow_mag ? 1.0 / timing.mag_rate_hz : dt;
      const double first = slow_mag ? timing.mag_first_sample_s : 0.0;
      const auto j = static_cast<long long>(std::floor((s.t_s - first) / period + 1e-9));
      if (j != last_mag_sample) {
        last_mag_sample = j;
        mag_truth_t = first + static_cast<double>(j) * period - timing.mag_lag_s;
        mag_reading = mag.measure(magPointAt(mag_truth_t));
      }
      row.mag_uT = mag_reading;
      row.mag_truth_t_s = mag_truth_t;
    }
    row.q_ns = q_ns[k];
    row.moving = s.moving;
    r.imu.push_back(row);
  }

  const LocalFrame frame(config.origin);
  r.gps = simulateGps(r.scenario, r.trajectory, frame, config.gps_rate_hz, Rng::stream(config.seed, kGps));
  return r;
}

}  // namespace headingd::sim
