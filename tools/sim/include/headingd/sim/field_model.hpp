#pragma once
// The magnetic field the person walks through, in NED and µT: the WMM main field at the
// place and date, turned about down by a local declination anomaly, plus the disturbances
// of the scenario's phases (field_model.cpp says how each is shaped).
#include <vector>

#include "headingd/core/quaternion.hpp"
#include "headingd/core/wmm.hpp"
#include "headingd/sim/rng.hpp"
#include "headingd/sim/scenario.hpp"

namespace headingd::sim {

class FieldModel {
 public:
  // `wmm` is the WMM at the scenario's place and date. A positive anomaly turns the
  // horizontal field east, so the local declination is WMM's + anomaly.
  FieldModel(const Scenario& scenario, const core::MagneticFieldElements& wmm, double declination_anomaly_deg, Rng rng);

  // The undisturbed local field (WMM turned by the anomaly).
  const core::Vec3& earthFieldNed_uT() const { return earth_ned_uT_; }
  double declinationDeg() const { return declination_deg_; }  // WMM's + anomaly

  // Disturbance at time t and position p (NED, m), to be added to earthFieldNed_uT().
  core::Vec3 disturbanceNed_uT(double t_s, const core::Vec3& position_ned_m) const;

 private:
  struct SpatialMode {  // one plane wave of the position-dependent indoor field
    core::Vec3 amplitude_uT;
    core::Vec3 wave_vector_rad_per_m;
    double phase_rad;
  };
  struct Transient {  // a magnetic object passing by (dipole fly-by shape)
    double t0_s;
    double half_width_s;
    core::Vec3 peak_uT;
  };
  struct PhaseField {
    core::Vec3 offset_uT;
    double spatial_sigma_uT;
  };
  PhaseField phaseField(std::size_t phase) const { return phase_fields_[phase]; }

  Scenario scenario_;
  core::Vec3 earth_ned_uT_;
  double declination_deg_;
  std::vector<PhaseField> phase_fields_;
  std::vector<SpatialMode> spatial_modes_;
  std::vector<Transient> transients_;
};

}  // namespace headingd::sim
