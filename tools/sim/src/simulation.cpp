#include "headingd/sim/simulation.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "headingd/sim/field_model.hpp"
#include "headingd/sim/trajectory_generator.hpp"

namespace headingd::sim {

namespace {

using core::Quat;
using core::Vec3;
constexpr double kDeg = std::numbers::pi / 180.0;

// Stream ids of Rng::stream: one per part of the model, so that they stay independent.
enum Stream : std::uint64_t { kTrajectory = 1, kField, kGyro, kAccel, kMag, kGps };

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// Sensor to body: zyx Euler angles of the mount. Without pitch and roll it is the yaw turn
// alone, bit for bit (the runs made before they existed stay the same).
Quat mountRotation(const SimConfig& c) {
  Quat q_bs = core::headingRotation(c.mount_yaw_deg * kDeg);
  if (c.mount_pitch_deg != 0.0 || c.mount_roll_deg != 0.0) {
    q_bs = (q_bs * Quat(Eigen::AngleAxisd(c.mount_pitch_deg * kDeg, Vec3::UnitY())) *
            Quat(Eigen::AngleAxisd(c.mount_roll_deg * kDeg, Vec3::UnitX())))
               .normalized();
  }
  return q_bs;
}

}  // namespace

const char* vectorSamplingName(VectorSampling v) {
  return v == VectorSampling::kIntervalMean ? "interval" : "point";
}

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

  const ImuErrorParams errors = imuErrorParams(config.imu_grade, field.earthFieldNed_uT().norm());
  TriadSensor gyro(errors.gyro, config.imu_rate_hz, Rng::stream(config.seed, kGyro));
  TriadSensor accel(errors.accel, config.imu_rate_hz, Rng::stream(config.seed, kAccel));
  TriadSensor mag(errors.mag, config.imu_rate_hz, Rng::stream(config.seed, kMag));
  r.gyro = {gyro.distortion(), gyro.offset(), gyro.whiteSigma()};
  r.accel = {accel.distortion(), accel.offset(), accel.whiteSigma()};
  r.mag = {mag.distortion(), mag.offset(), mag.whiteSigma()};

  const double dt = 1.0 / config.imu_rate_hz;
  const Vec3 gravity_ned(0.0, 0.0, kGravity_m_s2);
  Quat q_ns_previous = (r.trajectory.q_nb_before_start * r.q_bs).normalized();
  const auto& states = r.trajectory.states;
  r.imu.reserve(states.size());
  r.field_ned_uT.reserve(states.size());
  r.disturbance_ned_uT.reserve(states.size());
  Vec3 accel_previous = Vec3::Zero(), mag_previous = Vec3::Zero();  // point values at t_{k-1}
  for (const TruthState& s : states) {
    const Quat q_ns = (s.q_nb * r.q_bs).normalized();
    const Vec3 disturbance = field.disturbanceNed_uT(s.t_s, s.position_ned_m);
    const Vec3 field_ned = field.earthFieldNed_uT() + disturbance;
    // Row k's rate covers (t_{k-1}, t_k]: q_k = q_{k-1} ⊗ exp(½ ω_k Δt), the way the
    // estimator integrates a sample over the interval that ends at it.
    const Vec3 gyro_true = rateBetween(q_ns_previous, q_ns, dt);
    const Vec3 accel_point = q_ns.conjugate() * (s.accel_ned_mps2 - gravity_ned);  // f_s = R_nsᵀ (a_n - g_n)
    const Vec3 mag_point = q_ns.conjugate() * field_ned;
    // An interval-mean sensor reports the mean over (t_{k-1}, t_k] (trapezoid rule, in its own
    // turning axes); the first row has no interval before it.
    const bool mean = config.vector_sampling == VectorSampling::kIntervalMean && !r.imu.empty();
    const Vec3 accel_true = mean ? Vec3(0.5 * (accel_previous + accel_point)) : accel_point;
    const Vec3 mag_true = mean ? Vec3(0.5 * (mag_previous + mag_point)) : mag_point;
    accel_previous = accel_point;
    mag_previous = mag_point;
    ImuRow row;
    row.t_s = s.t_s;
    row.gyro_rad_s = gyro.measure(gyro_true);
    row.accel_m_s2 = accel.measure(accel_true);
    row.mag_uT = mag.measure(mag_true);
    row.q_ns = q_ns;
    row.moving = s.moving;
    r.imu.push_back(row);
    r.field_ned_uT.push_back(field_ned);
    r.disturbance_ned_uT.push_back(disturbance);
    q_ns_previous = q_ns;
  }

  const LocalFrame frame(config.origin);
  r.gps = simulateGps(r.scenario, r.trajectory, frame, config.gps_rate_hz, Rng::stream(config.seed, kGps));
  return r;
}

}  // namespace headingd::sim
