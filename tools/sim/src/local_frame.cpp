#include "headingd/sim/local_frame.hpp"

#include <GeographicLib/LocalCartesian.hpp>

namespace headingd::sim {

struct LocalFrame::Impl {
  GeographicLib::LocalCartesian enu;
};

LocalFrame::LocalFrame(const Geodetic& origin)
    : impl_(std::make_unique<Impl>(
          Impl{GeographicLib::LocalCartesian(origin.latitude_deg, origin.longitude_deg, origin.height_m)})) {}
LocalFrame::~LocalFrame() = default;
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;

Geodetic LocalFrame::toGeodetic(const core::Vec3& p) const {
  Geodetic g;
  // NED (north, east, down) -> ENU (east, north, up).
  impl_->enu.Reverse(p.y(), p.x(), -p.z(), g.latitude_deg, g.longitude_deg, g.height_m);
  return g;
}

core::Vec3 LocalFrame::toNed(const Geodetic& g) const {
  double east = 0.0, north = 0.0, up = 0.0;
  impl_->enu.Forward(g.latitude_deg, g.longitude_deg, g.height_m, east, north, up);
  return {north, east, -up};
}

}  // namespace headingd::sim
