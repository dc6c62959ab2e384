// The estimator (core::HeadingPipeline with the WMM) fed IMU samples and GPS observations
// decoded from the fuzz bytes: mostly plausible motion (so the filters get deep into their
// states) mixed with corrupt values (NaN, infinities, huge numbers, timestamps anywhere in
// the int64 range). Invariants after every call: the outputs are finite, the attitude
// quaternion has unit norm within 1e-6, and every sample given is either used or counted
// as rejected, with counters that match the verdicts returned.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>

#include "fuzz_check.hpp"
#include "headingd/core/heading_pipeline.hpp"
#include "headingd/core/wmm_coefficients.hpp"
#include "headingd/files/gzip_file.hpp"
#include "headingd/files/input_file.hpp"

using namespace headingd;

namespace {

const core::WorldMagneticModel& worldMagneticModel() {
  static const auto model = std::make_unique<core::WorldMagneticModel>(core::parseWmmCoefficients(
      files::readMaybeGzipFile(HEADINGD_FUZZ_WMM_COF, files::kWmmFileLimit), HEADINGD_FUZZ_WMM_COF));
  return *model;
}

// A value the input chooses: usually near `typical` (± spread), sometimes any double at all.
double value(FuzzedDataProvider& in, double typical, double spread) {
  switch (in.ConsumeIntegralInRange<int>(0, 15)) {
    case 0: return in.ConsumeFloatingPoint<double>();  // anything, huge values included
    case 1: return std::numeric_limits<double>::quiet_NaN();
    case 2:
      return in.ConsumeBool() ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    default: return typical + spread * (in.ConsumeIntegralInRange<int>(-1000, 1000) / 1000.0);
  }
}

// t_ns + step, saturated at the ends of the int64 range.
std::int64_t advance(std::int64_t t_ns, std::int64_t step) {
  std::int64_t next = 0;
  if (!__builtin_add_overflow(t_ns, step, &next)) return next;
  return step > 0 ? std::numeric_limits<std::int64_t>::max() : std::numeric_limits<std::int64_t>::min();
}

std::int64_t nextTime(FuzzedDataProvider& in, std::int64_t t_ns) {
  switch (in.ConsumeIntegralInRange<int>(0, 31)) {
    case 0: return in.ConsumeIntegral<std::int64_t>();  // a corrupt stamp, anywhere
    case 1: return t_ns;                                // duplicate
    case 2: return advance(t_ns, -in.ConsumeIntegralInRange<std::int64_t>(1, 2'000'000'000));       // backwards
    case 3: return advance(t_ns, in.ConsumeIntegralInRange<std::int64_t>(0, 100'000'000'000));      // a gap
    default: return advance(t_ns, in.ConsumeIntegralInRange<std::int64_t>(1'000'000, 20'000'000));  // 50..1000 Hz
  }
}

core::ImuSample sample(FuzzedDataProvider& in, std::int64_t t_ns) {
  core::ImuSample s;
  s.t_ns = t_ns;
  s.gyro_rad_s = core::Vec3(value(in, 0.0, 3.0), value(in, 0.0, 3.0), value(in, 0.0, 3.0));
  s.accel_m_s2 = core::Vec3(value(in, 0.0, 5.0), value(in, 0.0, 5.0), value(in, 9.81, 5.0));
  s.mag_uT = core::Vec3(value(in, 20.0, 30.0), value(in, 0.0, 30.0), value(in, 43.0, 30.0));
  s.has_mag = in.ConsumeIntegralInRange<int>(0, 7) != 0;
  return s;
}

core::GpsObservation observation(FuzzedDataProvider& in, std::int64_t t_ns) {
  core::GpsObservation g;
  g.t_ns = in.ConsumeIntegralInRange<int>(0, 15) == 0 ? in.ConsumeIntegral<std::int64_t>() : t_ns;
  g.fix_ok = in.ConsumeBool();
  if (in.ConsumeBool())
    g.position = core::GeodeticPosition{value(in, 0.0, 95.0), value(in, 0.0, 200.0), value(in, 0.0, 10.0)};
  if (in.ConsumeBool()) g.decimal_year = value(in, 2027.5, 5.0);
  if (in.ConsumeBool()) g.course_rad = value(in, 3.0, 4.0);
  if (in.ConsumeBool()) g.speed_mps = value(in, 1.5, 1.5);
  if (in.ConsumeBool()) g.hdop = value(in, 2.0, 2.0);
  if (in.ConsumeBool()) g.magvar_rad = value(in, 0.0, 4.0);
  return g;
}

void checkOutput(const core::HeadingPipeline& pipeline) {
  const core::HeadingOutput& o = pipeline.output();
  const core::EstimatorOutput& a = o.attitude;
  FUZZ_CHECK(a.q_nb.coeffs().allFinite());
  FUZZ_CHECK(std::abs(a.q_nb.norm() - 1.0) <= 1e-6);
  FUZZ_CHECK(std::isfinite(a.yaw_rad) && std::isfinite(a.heading_rad) && std::isfinite(a.head_height));
  FUZZ_CHECK(a.gyro_bias_rad_s.allFinite() && std::isfinite(a.dt_s) && a.dt_s >= 0.0);
  FUZZ_CHECK(std::isfinite(a.mag_gain) && std::isfinite(a.mag_innovation_rad) && std::isfinite(a.accel_disturbance));
  FUZZ_CHECK(std::isfinite(o.heading_mag_rad) && std::isfinite(o.heading_true_rad));
  FUZZ_CHECK(std::isfinite(o.declination_rad) && std::isfinite(o.mount_yaw_rad));
  FUZZ_CHECK(!std::isnan(o.declination_sigma_rad) && !std::isnan(o.mount_yaw_sigma_rad));  // ∞: unknown
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  core::HeadingPipeline pipeline(core::EstimatorParams{}, in.ConsumeBool() ? &worldMagneticModel() : nullptr);
  std::int64_t t_ns = in.ConsumeIntegralInRange<std::int64_t>(0, 2'000'000'000'000'000'000);
  std::uint64_t given = 0, first = 0, used = 0, dated_epochs = 0;
  core::SampleCounters verdicts;
  while (in.remaining_bytes() > 0) {
    if (in.ConsumeIntegralInRange<int>(0, 19) == 0) {
      const core::GpsObservation g = observation(in, t_ns);
      dated_epochs += g.decimal_year ? 1 : 0;
      pipeline.processGps(g);
      checkOutput(pipeline);
      continue;
    }
    t_ns = nextTime(in, t_ns);
    const core::SampleVerdict verdict = pipeline.process(sample(in, t_ns));
    ++given;
    used += core::sampleUsed(verdict) ? 1 : 0;
    switch (verdict) {
      case core::SampleVerdict::kFirst: ++first; break;
      case core::SampleVerdict::kAccepted: ++verdicts.accepted; break;
      case core::SampleVerdict::kGap: ++verdicts.gaps; break;
      case core::SampleVerdict::kClockJump: ++verdicts.clock_jumps; break;
      case core::SampleVerdict::kDuplicateTime: ++verdicts.duplicate_time; break;
      case core::SampleVerdict::kBackwardsTime: ++verdicts.backwards_time; break;
      case core::SampleVerdict::kNonFinite: ++verdicts.non_finite; break;
      case core::SampleVerdict::kOutOfRange: ++verdicts.out_of_range; break;
    }
    checkOutput(pipeline);
  }
  const core::SampleCounters c = pipeline.estimator().counters().samples;
  FUZZ_CHECK(first <= 1);
  FUZZ_CHECK(c.accepted == verdicts.accepted && c.gaps == verdicts.gaps && c.clock_jumps == verdicts.clock_jumps);
  FUZZ_CHECK(c.duplicate_time == verdicts.duplicate_time && c.backwards_time == verdicts.backwards_time);
  FUZZ_CHECK(c.non_finite == verdicts.non_finite && c.out_of_range == verdicts.out_of_range);
  const std::uint64_t rejected = c.duplicate_time + c.backwards_time + c.non_finite + c.out_of_range;
  FUZZ_CHECK(used == first + c.accepted + c.gaps + c.clock_jumps);
  FUZZ_CHECK(given == used + rejected);
  // A date not believed is one of the epochs' dates, and a value left out (gps_date_check.hpp).
  FUZZ_CHECK(pipeline.gpsDatesNotBelieved() <= dated_epochs);
  FUZZ_CHECK(pipeline.gpsDatesNotBelieved() <= pipeline.gpsValuesIgnored());
  return 0;
}
