#pragma once
// True heading: the attitude estimator plus what GPS and the World Magnetic Model add
// to it: the WMM field at the GPS position for the disturbance tests (Henriksson §4.2),
// the mounting yaw from the gait, and the declination from WMM, GPS course (ch. 5) and the
// receiver's magnetic variation. Pure and deterministic like the Estimator; the caller feeds
// IMU samples and GPS epochs in time order on one time axis.
#include <cstdint>
#include <optional>

#include "headingd/core/declination_estimator.hpp"
#include "headingd/core/epoch_compass.hpp"
#include "headingd/core/estimator.hpp"
#include "headingd/core/gait_mount_yaw.hpp"
#include "headingd/core/gps_date_check.hpp"
#include "headingd/core/gps_observation.hpp"
#include "headingd/core/sensor_units_check.hpp"
#include "headingd/core/wmm.hpp"

namespace headingd::core {

// Which sources the declination came from (a bit set; none = no declination known yet).
enum DeclinationSource : unsigned { kDeclNone = 0, kDeclWmm = 1, kDeclGps = 2, kDeclReceiver = 4 };
// "none", "wmm", "wmm+gps", "gps+receiver", …
const char* declinationSourceName(unsigned sources);

struct HeadingOutput {
  EstimatorOutput attitude;      // the sensor's attitude, magnetic north
  double heading_mag_rad = 0.0;  // sensor x-axis heading from magnetic north
  double declination_rad = 0.0;
  double declination_sigma_rad = 0.0;
  unsigned declination_sources = kDeclNone;
  double mount_yaw_rad = 0.0;  // sensor turned from body about down (gait_mount_yaw.hpp)
  double mount_yaw_sigma_rad = 0.0;
  double heading_true_rad = 0.0;  // the body's heading from geographic north
  // 1-sigma of heading_mag_rad (the estimator's heading_sigma_rad), and of heading_true_rad:
  // that with the mounting yaw's and the declination's (∞ while no declination is known).
  double heading_mag_sigma_rad = 0.0;
  double heading_true_sigma_rad = 0.0;

  // The magnetic heading and its sigma, and the true heading and its sigma from them with the
  // declination and the mounting yaw already here.
  void setMagneticHeading(double heading_rad, double sigma_rad);
};

class HeadingPipeline {
 public:
  // wmm may be null (no model: no reference field, declination from GPS/receiver only).
  HeadingPipeline(const EstimatorParams& params, const WorldMagneticModel* wmm);

  SampleVerdict process(const ImuSample& sample);
  // Values it cannot use (non-finite, a latitude beyond ±90°, a negative speed or HDOP, a
  // variation beyond ±180°) are left out of the epoch and counted: gpsValuesIgnored(). A date
  // the model should not be evaluated on (gps_date_check.hpp) is counted there and in
  // gpsDatesNotBelieved(); the model is evaluated on the date in use instead.
  // Returns what the first value left out was (for a log line), nullptr when all were used.
  const char* processGps(const GpsObservation& gps);

  // A configured place (configured_place.hpp): the World Magnetic Model there on that date
  // gives the reference field and the WMM declination until a GPS fix gives a position. False
  // (and nothing changes) without a model or where its field is not finite.
  bool setPlace(const GeodeticPosition& position, double decimal_year);
  // The date GPS dates are checked against until one is believed (gps_date_check.hpp): the
  // system's at start-up. False (nothing changes) without a model or outside its validity.
  bool seedGpsDate(double decimal_year);

  const HeadingOutput& output() const { return out_; }
  const Estimator& estimator() const { return estimator_; }
  std::uint64_t gpsEpochsUsedForDeclination() const { return course_minus_heading_.epochs(); }
  std::uint64_t gpsValuesIgnored() const { return gps_values_ignored_; }
  // Whether the samples look like SI units (sensor_units_check.hpp).
  const SensorUnitsCheck& sensorUnits() const { return units_; }
  std::uint64_t gpsDatesNotBelieved() const { return gps_dates_ ? gps_dates_->notBelieved() : 0; }

 private:
  bool courseGatesPass(const GpsObservation& gps, double sensor_heading) const;
  std::size_t compassMinSamples(std::int64_t gps_t_ns) const;
  // The model's reference field and declination at a position; false if not finite there.
  bool useModelAt(const GeodeticPosition& position, double decimal_year);
  void updateDeclination();  // at GPS epochs (and a configured place): the sources change only then
  void updateOutput();       // every sample: cheap, no allocation

  EstimatorParams p_;
  const WorldMagneticModel* wmm_;
  Estimator estimator_;
  GaitMountYawEstimator gait_;
  CourseMinusHeading course_minus_heading_;
  EpochCompass epoch_compass_;  // the heading compared with the course (epoch_compass.hpp)
  HeadingOutput out_;

  std::optional<double> wmm_declination_rad_;
  std::optional<double> receiver_magvar_rad_;
  std::int64_t last_disturbed_ns_ = 0;
  bool ever_disturbed_ = false;
  std::optional<std::int64_t> last_walking_gps_ns_;
  // The previous GPS epoch, for the walking-straight gate.
  std::optional<std::int64_t> previous_gps_ns_;
  double previous_course_rad_ = 0.0;
  double previous_sensor_heading_rad_ = 0.0;
  bool previous_epoch_added_ = false;  // the previous GPS epoch counted for the declination
  std::uint64_t gps_values_ignored_ = 0;
  std::optional<GpsDateCheck> gps_dates_;  // with a model
  SensorUnitsCheck units_;
};

}  // namespace headingd::core
