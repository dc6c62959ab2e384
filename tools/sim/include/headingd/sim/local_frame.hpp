#pragma once
// Local NED positions around a geodetic origin and back, through GeographicLib's
// LocalCartesian (which works in ENU: the conversion lives here and nowhere else).
#include <memory>

#include "headingd/core/quaternion.hpp"

namespace headingd::sim {

struct Geodetic {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double height_m = 0.0;  // above the WGS-84 ellipsoid
};

class LocalFrame {
 public:
  explicit LocalFrame(const Geodetic& origin);
  ~LocalFrame();
  LocalFrame(LocalFrame&&) noexcept;
  LocalFrame& operator=(LocalFrame&&) noexcept;

  Geodetic toGeodetic(const core::Vec3& position_ned_m) const;
  core::Vec3 toNed(const Geodetic& g) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace headingd::sim
