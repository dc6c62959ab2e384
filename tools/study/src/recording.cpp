#include "headingd/study/recording.hpp"

#include <filesystem>
#include <limits>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "headingd/sim/rng.hpp"

namespace headingd::study {

using core::Vec3;

Recording readBroadTrial(const std::string& path) {
  Recording r;
  r.name = std::filesystem::path(path).filename().string();
  if (r.name.ends_with(".csv.gz")) r.name.resize(r.name.size() - 7);
  // All rows in memory: a study replays each trial under many estimator settings. Both
  // readers parse in place (files::CsvRowReader); only the values asked for are held.
  r.samples = files::readImuCsv(path);
  const auto ref = files::readNumericCsv(path, {"ref_w", "ref_x", "ref_y", "ref_z", "moving"});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // q_enu = q_EN ⊗ q_nb (core::nedToEnu); q_EN is a half turn, so q_nb = q_EN⁻¹ ⊗ q_enu, and
  // nedToEnu applied to q_enu gives q_EN ⊗ q_enu = -q_EN⁻¹ ⊗ q_enu, the same rotation.
  for (std::size_t i = 0; i < ref.rows; ++i) {
    const core::Quat q_enu(ref.column("ref_w")[i], ref.column("ref_x")[i], ref.column("ref_y")[i],
                           ref.column("ref_z")[i]);
    r.truth_nb.push_back(hasTruth(q_enu) ? core::nedToEnu(q_enu.normalized()) : core::Quat(nan, nan, nan, nan));
    r.moving.push_back(ref.column("moving")[i] == 1.0);
  }
  if (r.samples.size() > 1) {
    r.rate_hz = static_cast<double>(r.samples.size() - 1) * 1e9 /
                static_cast<double>(r.samples.back().t_ns - r.samples.front().t_ns);
  }
  return r;
}

Recording fromSimulation(const sim::SimResult& result, std::string name) {
  Recording r;
  r.name = std::move(name);
  r.rate_hz = result.config.imu_rate_hz;
  const core::Quat true_to_magnetic = core::headingRotation(-result.declination_deg * core::kRadPerDeg);
  for (const sim::ImuRow& row : result.imu) {
    r.samples.push_back(sim::imuSample(row));
    r.truth_nb.push_back((true_to_magnetic * row.q_ns).normalized());
    r.moving.push_back(row.moving);
  }
  r.reference_field_uT = 1e-3 * result.wmm.f_nT;
  r.reference_inclination_rad = result.wmm.inclination_deg * core::kRadPerDeg;
  return r;
}

void startOffBy(Recording& r, double angle_rad, std::uint64_t seed) {
  if (r.samples.empty()) return;
  core::ImuSample& first = r.samples.front();
  // An axis perpendicular to the measured gravity, so the whole angle is tilt.
  sim::Rng rng = sim::Rng::stream(seed, 999);
  Vec3 axis = rng.unitVector().cross(first.accel_m_s2.normalized());
  if (axis.norm() < 1e-6) axis = Vec3::UnitX();
  const core::Quat turn(Eigen::AngleAxisd(angle_rad, axis.normalized()));
  first.accel_m_s2 = turn * first.accel_m_s2;
  first.mag_uT = turn * first.mag_uT;
}

core::Vec3 referenceRate(const Recording& r, std::size_t i) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (i + 1 >= r.size() || !hasTruth(r.truth_nb[i]) || !hasTruth(r.truth_nb[i + 1])) return Vec3::Constant(nan);
  const double dt_s = 1e-9 * static_cast<double>(r.samples[i + 1].t_ns - r.samples[i].t_ns);
  if (!(dt_s > 0.0)) return Vec3::Constant(nan);
  core::Quat step = r.truth_nb[i].conjugate() * r.truth_nb[i + 1];
  if (step.w() < 0.0) step.coeffs() = -step.coeffs();
  return 2.0 * step.vec() / dt_s;
}

}  // namespace headingd::study
