#include "headingd/sim/field_model.hpp"

#include <cmath>
#include <numbers>

#include "headingd/core/angles.hpp"
#include "headingd/sim/gait.hpp"

namespace headingd::sim {

namespace {
using core::Vec3;
constexpr double kPi = std::numbers::pi;
using core::kRadPerDeg;
// Offsets and the spatial field fade in and out over this time at a phase change (walking
// in through a door).
constexpr double kBlendS = 2.0;
constexpr int kSpatialModes = 6;
}  // namespace

FieldModel::FieldModel(const Scenario& scenario, const core::MagneticFieldElements& wmm, double anomaly_deg, Rng rng)
    : scenario_(scenario),
      earth_ned_uT_(core::headingRotation(anomaly_deg * kRadPerDeg) * core::magneticFieldNed_uT(wmm)),
      declination_deg_(wmm.declination_deg + anomaly_deg) {
  // Per phase: the given offset plus a seeded one of the given size.
  for (const Phase& p : scenario.phases) {
    const Vec3 random_offset =
        p.field.random_offset_uT > 0.0 ? Vec3(p.field.random_offset_uT * rng.unitVector()) : Vec3::Zero();
    phase_fields_.push_back({p.field.offset_ned_uT + random_offset, p.field.spatial_sigma_uT});
  }
  // Position-dependent field of a building: a few plane waves, horizontal wavelengths of
  // 2-12 m; amplitudes scaled so each axis has an RMS of about 1 (times the phase's sigma).
  for (int i = 0; i < kSpatialModes; ++i) {
    const double wavelength_m = rng.uniform(2.0, 12.0);
    const double direction = rng.uniform(0.0, 2.0 * kPi);
    const Vec3 k = (2.0 * kPi / wavelength_m) * Vec3(std::cos(direction), std::sin(direction), 0.0);
    const Vec3 amplitude = std::sqrt(2.0 / kSpatialModes) * rng.gaussian3();
    spatial_modes_.push_back({amplitude, k, rng.uniform(0.0, 2.0 * kPi)});
  }
  // Transients: a Poisson process per phase; a dipole passing at closest distance d with
  // speed v gives |B| ∝ r⁻³ = (d² + v²t²)^(-3/2), i.e. (1 + (t/w)²)^(-3/2) with w = d/v.
  double start = 0.0;
  for (const Phase& p : scenario.phases) {
    if (p.field.transients_per_min > 0.0 && p.field.transient_peak_uT > 0.0) {
      const double mean_gap_s = 60.0 / p.field.transients_per_min;
      for (double t = start + rng.exponential(mean_gap_s); t < start + p.duration_s; t += rng.exponential(mean_gap_s)) {
        const double peak = p.field.transient_peak_uT * rng.uniform(0.3, 1.0);
        transients_.push_back({t, rng.uniform(0.4, p.field.transient_max_half_width_s), peak * rng.unitVector()});
      }
    }
    start += p.duration_s;
  }
}

Vec3 FieldModel::disturbanceNed_uT(double t_s, const Vec3& position_ned_m) const {
  const PhaseTime pt = phaseAt(scenario_, t_s);
  PhaseField f = phaseField(pt.index);
  if (pt.index > 0 && pt.since_start_s < kBlendS) {
    const PhaseField before = phaseField(pt.index - 1);
    const double w = smootherstep(pt.since_start_s / kBlendS);
    f.offset_uT = before.offset_uT + w * (f.offset_uT - before.offset_uT);
    f.spatial_sigma_uT = before.spatial_sigma_uT + w * (f.spatial_sigma_uT - before.spatial_sigma_uT);
  }
  Vec3 d = f.offset_uT;
  if (f.spatial_sigma_uT > 0.0) {
    for (const SpatialMode& m : spatial_modes_) {
      d += f.spatial_sigma_uT * std::sin(m.wave_vector_rad_per_m.dot(position_ned_m) + m.phase_rad) * m.amplitude_uT;
    }
  }
  for (const Transient& tr : transients_) {
    const double u = (t_s - tr.t0_s) / tr.half_width_s;
    d += tr.peak_uT * std::pow(1.0 + u * u, -1.5);
  }
  return d;
}

}  // namespace headingd::sim
