#include "headingd/core/calibrated_imu_stream.hpp"

#include <algorithm>

namespace headingd::core {

ImuSample CalibratedImuStream::apply(const ImuSample& raw) {
  if (!calibrated_) return raw;
  ImuSample out = correction_.apply(raw);
  if (!raw.has_mag) return out;
  const double dt_s = have_last_mag_ ? static_cast<double>(raw.t_ns - last_mag_t_ns_) * 1e-9 : 0.0;
  last_mag_t_ns_ = raw.t_ns;
  have_last_mag_ = true;
  // A backwards or huge step (clock jump) feeds dt 0 resp. is capped inside update().
  if (!fit_.update(raw.mag_uT, out.mag_uT, std::max(dt_s, 0.0))) out.mag_uT = raw.mag_uT;
  return out;
}

}  // namespace headingd::core
