#pragma once
// The data of Kok & Schön (2016) §8: a sensor at rest for 100 samples, then rotating about
// all three axes about the accelerometer's origin (so zero acceleration), at 100 Hz, with the
// sensor errors of Table 2 drawn per run. The errors are made by the simulator's triad model
// (headingd_sim, TriadSensor: y = D x + o + n with D = D_diag D_skew D_rot, eqs. 31-32).
#include <cstdint>
#include <string_view>
#include <vector>

#include "headingd/core/imu_sample.hpp"

namespace headingd::calib_montecarlo {

enum class KsVariant {
  kShort,        // K&S §8: 100 still + 300 rotating samples (4 s)
  kLong,         // 100 still + 2900 rotating samples (30 s), slower turns, as a person calibrates
  kFiveMinutes,  // 100 still + 29900 rotating (5 min): times the ML step on a recording's length
};
// Throws std::invalid_argument for anything but "short", "long" and "5min".
KsVariant parseVariant(std::string_view name);
const char* variantName(KsVariant v);

struct KsTruth {
  core::Mat3 mag_D = core::Mat3::Identity();  // y_m = D m_b + o, |m_b| = field_norm_uT
  core::Vec3 mag_offset_uT = core::Vec3::Zero();
  core::Vec3 gyro_bias_rad_s = core::Vec3::Zero();
  core::Vec3 gyro_sigma = core::Vec3::Zero();   // rad/s per sample
  core::Vec3 accel_sigma = core::Vec3::Zero();  // m/s²
  core::Vec3 mag_sigma_uT = core::Vec3::Zero();
  double dip_rad = 0.0;
  double field_norm_uT = 0.0;
};

struct KsRun {
  std::vector<core::ImuSample> samples;
  std::vector<core::Quat> q_nb;               // true attitude per sample (NED, x magnetic north)
  std::vector<core::Vec3> mag_noise_free_uT;  // D m_b + o: what the magnetometer reads without noise
  std::size_t stationary_samples = 100;
  KsTruth truth;
};

// The local field of K&S's study, Linköping: WMM2025 at 58.41° N, 15.62° E, 2026-06-01
// (headingd-wmm): F = 51.53 µT, inclination 72.21°.
inline constexpr double kLinkopingFieldNorm_uT = 51.533;
inline constexpr double kLinkopingDip_deg = 72.213;
inline constexpr double kGravity_m_s2 = 9.81;

struct KsNoiseScale {
  // Multiplies every σ drawn from Table 2 (1 = the paper's settings); tests use less noise
  // to check recovery against tight tolerances.
  double factor = 1.0;
  // Table 2 gives Σω ~ U(1e-3, 1e-2), Σa, Σm ~ U(1e-3, 1e-1). Read literally these are
  // variances (σω up to 0.1 rad/s, σm up to 0.32 of the field); read as standard deviations
  // they match the "physically reasonable" sensors the text describes (σω 1e-3..1e-2 rad/s).
  bool table_values_are_sigmas = false;
};

KsRun simulateKokSchonRun(KsVariant variant, std::uint64_t seed, KsNoiseScale noise = {});

// Heading RMSE (rad) after calibrating with (D, o) as K&S Fig. 8 scores it, isolated from
// the sensor noise: at every sample the noise-free reading is calibrated, m_b = D⁻¹(y - o),
// levelled with the true roll and pitch, and its heading compared with the true heading.
double headingRmseRad(const KsRun& run, const core::Mat3& D, const core::Vec3& offset_uT);

}  // namespace headingd::calib_montecarlo
