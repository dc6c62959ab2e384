#pragma once
// One simulation run: scenario -> true motion -> true field -> IMU samples with errors, GPS
// epochs, and the truth to score against. No file I/O here (output.hpp writes the files).
//
// Time axis: the first IMU row is t = 0, row k is t = k / imu_rate_hz. GPS epoch j is at
// t = j / gps_rate_hz on the same axis; its NMEA UTC is the date at 00:00:00 plus
// kStartTimeOfDayS plus t. A replay therefore recovers t of a sentence as
// UTC(sentence) - (date 12:00:00 UTC).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "headingd/core/imu_sample.hpp"
#include "headingd/core/quaternion.hpp"
#include "headingd/core/wmm.hpp"
#include "headingd/sim/gps_model.hpp"
#include "headingd/sim/imu_model.hpp"
#include "headingd/sim/local_frame.hpp"
#include "headingd/sim/scenario.hpp"
#include "headingd/sim/trajectory.hpp"

namespace headingd::sim {

inline constexpr double kStartTimeOfDayS = 12.0 * 3600.0;  // t = 0 is 12:00:00 UTC

// How the accelerometer and magnetometer sample: the mean over the interval that ends at the
// sample time, as the gyro's rate is (an IMU that integrates and dumps, or filters over its
// sample period; BROAD's real IMU reads that way), or the value at the sample time.
enum class VectorSampling { kIntervalMean, kPoint };
const char* vectorSamplingName(VectorSampling v);
// Throws std::invalid_argument for an unknown name.
VectorSampling parseVectorSampling(std::string_view name);

struct SimConfig {
  std::string scenario = "thesis-declination";
  std::uint64_t seed = 1;
  Geodetic origin{59.33, 18.07, 0.0};  // Stockholm, ground level on the ellipsoid
  int year = 2026;
  int month = 6;
  int day = 1;
  double decl_anomaly_deg = 0.0;  // local declination = WMM's + this
  double mount_yaw_deg = 0.0;     // sensor axes = body axes turned by this about body z
  // ... then by this about the turned y axis, then by roll about the turned x axis (zyx, as
  // Euler angles): a sensor mounted flat (pitch 90: its x up), upside down (roll 180: its z
  // up, as a phone lying screen-up whose z leaves the screen), in a pocket.
  double mount_pitch_deg = 0.0;
  double mount_roll_deg = 0.0;
  double imu_rate_hz = 100.0;
  double gps_rate_hz = 1.0;
  ImuGrade imu_grade = ImuGrade::kConsumer;
  VectorSampling vector_sampling = VectorSampling::kIntervalMean;
  // How late the accelerometer reads against the gyro (s), instead of what the grade draws
  // (phones: 0-5 ms; the other grades: none): a sensor whose delay has to be learned.
  std::optional<double> accel_lag_s;
  std::string talker = "GP";
};

// Throws std::invalid_argument naming the field when a value is out of range.
void validate(const SimConfig& config);

// A configuration with everything else at its default.
SimConfig simConfig(std::string scenario, std::uint64_t seed, ImuGrade grade, double imu_rate_hz);

struct ImuRow {
  double t_s = 0.0;
  core::Vec3 gyro_rad_s = core::Vec3::Zero();  // sensor axes
  core::Vec3 accel_m_s2 = core::Vec3::Zero();  // specific force, sensor axes
  core::Vec3 mag_uT = core::Vec3::Zero();
  core::Quat q_ns = core::Quat::Identity();  // true sensor-to-NED attitude (BROAD's ref, but NED)
  bool moving = false;
  // The gyro's true bias in this row: constant offset + drifting bias (sensor axes, rad/s),
  // what an estimator's bias estimate should converge to (the scale error D - I comes on top).
  core::Vec3 gyro_bias_rad_s = core::Vec3::Zero();
  // The time whose true field and attitude the magnetometer reading of this row describes:
  // t_s, or for a late and slower magnetometer (SensorTiming) its last sample's time - lag.
  double mag_truth_t_s = 0.0;
};

// The estimator's input for a row: time in nanoseconds, the three triads.
core::ImuSample imuSample(const ImuRow& row);

struct DrawnTriad {  // what TriadSensor drew: y = D x + o + b(t) + n
  core::Mat3 distortion = core::Mat3::Identity();
  core::Vec3 offset = core::Vec3::Zero();
  core::Vec3 white_sigma = core::Vec3::Zero();
  double full_scale = 0.0;  // |y_i| at most this; 0: no limit
};

struct SimResult {
  SimConfig config;
  Scenario scenario;
  core::MagneticFieldElements wmm;  // at the origin and date
  std::string wmm_model_name;
  double declination_deg = 0.0;              // local truth: WMM's + anomaly
  core::Quat q_bs = core::Quat::Identity();  // sensor to body (the mount)
  Trajectory trajectory;
  std::vector<core::Vec3> field_ned_uT;  // true total field at each IMU row
  std::vector<core::Vec3> disturbance_ned_uT;
  std::vector<ImuRow> imu;
  std::vector<GpsEpoch> gps;
  DrawnTriad gyro, accel, mag;
  SensorTiming timing;  // when the accelerometer and magnetometer sample (phone grade)
};

inline constexpr double kGravity_m_s2 = 9.81;  // g_n = (0, 0, +9.81) in NED

SimResult simulate(const SimConfig& config, const core::WorldMagneticModel& wmm);
// The same for a scenario made elsewhere (tests that set a motion's parameters themselves);
// config.scenario only names it.
SimResult simulate(const SimConfig& config, const Scenario& scenario, const core::WorldMagneticModel& wmm);

}  // namespace headingd::sim
