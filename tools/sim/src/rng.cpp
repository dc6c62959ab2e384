#include "headingd/sim/rng.hpp"

#include <cmath>
#include <numbers>

namespace headingd::sim {

namespace {
// SplitMix64's finaliser: spreads (seed, stream) pairs over the engine's seed space so that
// neighbouring seeds and stream ids do not give correlated mt19937_64 states.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
}  // namespace

Rng Rng::stream(std::uint64_t seed, std::uint64_t stream_id) { return Rng(mix(mix(seed) ^ mix(~stream_id))); }

double Rng::uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

double Rng::uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }

double Rng::gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double u1 = 1.0 - uniform01();  // (0, 1]: log(0) never happens
  const double u2 = uniform01();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double a = 2.0 * std::numbers::pi * u2;
  spare_ = r * std::sin(a);
  has_spare_ = true;
  return r * std::cos(a);
}

core::Vec3 Rng::unitVector() {
  // Normalised Gaussian vectors are uniform on the sphere; the draw is repeated in the
  // (practically impossible) case of a zero vector.
  for (;;) {
    const core::Vec3 v = gaussian3();
    const double n = v.norm();
    if (n > 1e-9) return v / n;
  }
}

double Rng::exponential(double mean) { return -mean * std::log(1.0 - uniform01()); }

}  // namespace headingd::sim
