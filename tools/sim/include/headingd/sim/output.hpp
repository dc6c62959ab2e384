#pragma once
// The files headingd-sim writes, each to a stream (main.cpp opens the files):
//   imu.csv          BROAD's layout (t,gyr_*,acc_*,mag_*,ref_w..z,moving), but ref is the
//                    TRUE sensor-to-NED quaternion (BROAD's ref is sensor-to-ENU, magnetic)
//   gps.nmea         GGA, RMC, VTG per epoch, in time order
//   truth.csv        per IMU row: headings, declination, position, pose, field
//   gps_truth.csv    per GPS epoch: what the receiver reported next to the truth
//   sensor_errors.toml  the drawn IMU errors (D, o, white σ per triad) and the run's settings
// Numbers are printed with snprintf, so the same result gives the same bytes.
#include <ostream>

#include "headingd/sim/simulation.hpp"

namespace headingd::sim {

void writeImuCsv(std::ostream& out, const SimResult& r);
void writeTruthCsv(std::ostream& out, const SimResult& r);
void writeNmea(std::ostream& out, const SimResult& r);
void writeGpsTruthCsv(std::ostream& out, const SimResult& r);
void writeSensorErrors(std::ostream& out, const SimResult& r);

// Columns of truth.csv, for readers and tests.
inline constexpr const char* kTruthHeader =
    "t,heading_true_deg,heading_mag_deg,declination_deg,lat_deg,lon_deg,mount_yaw_deg,activity,indoor,moving,"
    "pitch_deg,roll_deg,heading_redefined_true_deg,head_height,path_heading_deg,speed_mps,north_m,east_m,down_m,"
    "field_n_uT,field_e_uT,field_d_uT,disturbance_uT,body_qw,body_qx,body_qy,body_qz,gyro_bias_x,gyro_bias_y,"
    "gyro_bias_z";
inline constexpr const char* kImuHeader =
    "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z,ref_w,ref_x,ref_y,ref_z,moving";

}  // namespace headingd::sim
