#pragma once
// Quasi-static field (QSF) detection, Renaudin & Combettes (2014) §5: whether a field the
// sensor measures (the magnetic field, or the specific force) is constant in the navigation
// frame, whatever its value. Indoors the field is often wrong but static (steel furniture, a
// radiator), and then its change in sensor axes is the sensor's rotation alone: what the QSF,
// MARU and AGU updates of §6 observe.
//
// A period starts once a whole window (window_s, N·Ts of eq. 33) passes three tests, and lasts
// while every new sample keeps them:
//  - eq. 33: the RMS over the window of |f| - ξ_ref below max_norm_rms, ξ_ref the mean norm of
//    the period's first reference_s (N_first·Ts) of samples;
//  - eq. 34: every |f| - ξ_ref within max_norm_deviation (outliers);
//  - the direction, which a norm cannot see (a field that turns in the navigation frame keeps
//    its strength): every sample of the window carried through the gyro into one frame, their
//    RMS spread about their mean below max_direction_rms. Over the window the gyro's error
//    moves that frame by its bias times window_s (10 mrad/s over 1 s: 0.5 µT of a 50 µT field).
// Thresholds are in the field's own unit (µT, m/s²). A period that fails a test ends, and the
// next needs a whole window again.
//
// A phone's magnetometer can be five times noisier than a lab part's (0.3 to 1.5 µT per
// sample), and a threshold that suits one never passes the other (the simulated phone grade's
// noisiest draws: no period in a whole run). So each threshold is the configured value or a
// multiple of the window's own white noise, whichever is larger (at most kMaxOverConfigured
// times the configured value). The noise comes from the differences of successive samples
// (E|x_k - x_k-1|² = 2σ² for white noise), which a field that changes slowly hardly moves: a
// window whose spread about its mean (or ξ_ref) is no larger than its sample-to-sample noise
// says is static; one with a trend or a step is not (von Neumann's ratio of the two). A noise
// floor learned as the quietest window of the last minute (noise_floor.hpp) would instead
// take a field that never stops turning for noise.
#include <cstdint>
#include <vector>

#include "headingd/core/quaternion.hpp"

namespace headingd::core {

struct QuasiStaticFieldParams {
  double window_s;            // N·Ts (eq. 33); 0 turns the detection off
  double reference_s;         // N_first·Ts: ξ_ref is the mean norm of the period's first samples
  double max_norm_rms;        // γ1 of eq. 33, as an RMS in the field's unit
  double max_norm_deviation;  // γ2 of eq. 34
  double max_direction_rms;   // the carried samples' spread (field unit)
};

// The attitude the gyro alone gives, from wherever it started: q(t + dt) = q(t) ⊗ increment
// (Henriksson eq. 2.34), never corrected. One serves every detector of a sensor.
class GyroFrame {
 public:
  // The sensor's rotation over one gyro sample (bias taken off): every one, also where a
  // field has no new sample (a slower magnetometer).
  void advance(const Quat& increment) {
    q_ = q_ * increment;
    // Kept at unit length without a square root: after one product |q|² is 1 to a few ulps,
    // and there 1/|q| = 1.5 - 0.5 |q|² to rounding (as AttitudeEkf::normalise).
    q_.coeffs() *= 1.5 - 0.5 * q_.squaredNorm();
  }
  const Quat& frameFromSensor() const { return q_; }

 private:
  Quat q_ = Quat::Identity();
};

class QuasiStaticFieldDetector {
 public:
  explicit QuasiStaticFieldDetector(const QuasiStaticFieldParams& params);

  // A new field sample in sensor axes, and the sensor's attitude in a frame that the gyro alone
  // carries (GyroFrame: any such frame, the same for every sample; the detector compares
  // samples within a window only, so the frame's drift over longer times does not matter);
  // dt_s is the time since the previous sample. Returns whether the field is quasi-static now.
  bool add(const Vec3& field, const Quat& frame_from_sensor, double dt_s);
  // After a gap: the gyro frame is not valid across it. Counters are kept.
  void restart();

  bool quasiStatic() const { return in_period_; }
  double referenceNorm() const { return reference_norm_; }  // ξ_ref of the current period
  double periodSeconds() const { return in_period_ ? period_s_ : 0.0; }
  std::size_t windowSamples() const { return size_; }  // field samples in the window now
  // The white noise per axis that the window's successive samples show (field unit; 0 until
  // the window holds two).
  double sampleNoiseSigma() const;
  std::uint64_t periods() const { return periods_; }
  double totalSeconds() const { return total_s_; }

 private:
  struct Entry {
    double t_s;
    double norm;
    Vec3 carried;  // the sample in the frame the gyro carries (GyroFrame)
    // Squared differences to the sample before (0 for the first after a restart).
    double norm_step2;
    double carried_step2;
  };
  void push(const Entry& e);
  void dropOlderThan(double t_s);
  void recomputeSums();
  bool windowFull() const;
  // Squares of: the norm's RMS about a reference; the carried samples' spread about their mean.
  double normMeanSquare(double reference) const;
  double directionMeanSquare() const;
  // The white noise's variance the successive differences show: of the norm (σ²), of the
  // carried vector (3 σ² for three axes of σ, the spread a still field's samples have).
  double normNoise2() const;
  double directionNoise2() const;
  // Eq. 34 over the window against a reference found from its first reference_s: starts a
  // period if it holds; otherwise remembers the latest outlier so that the scan waits for it
  // to leave the window.
  bool tryStart(double max_norm_rms2, double max_norm_deviation2);
  const Entry& at(std::size_t i) const { return ring_[(head_ + i) & (ring_.size() - 1)]; }

  QuasiStaticFieldParams p_;
  double t_s_ = 0.0;         // of field samples since the restart
  std::vector<Entry> ring_;  // the window, oldest at head_; grows to fit
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::size_t pushes_since_recompute_ = 0;
  double sum_norm_ = 0.0;
  double sum_norm2_ = 0.0;
  Vec3 sum_carried_ = Vec3::Zero();
  double sum_carried2_ = 0.0;
  // Of the pairs within the window (each entry's step but the oldest's).
  double sum_norm_step2_ = 0.0;
  double sum_carried_step2_ = 0.0;
  double wait_until_s_ = 0.0;  // an outlier is in the window until then
  bool in_period_ = false;
  double reference_norm_ = 0.0;
  double period_s_ = 0.0;
  std::uint64_t periods_ = 0;
  double total_s_ = 0.0;
};

}  // namespace headingd::core
