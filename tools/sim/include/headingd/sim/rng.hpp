#pragma once
// Portable random numbers for the simulator. The standard distributions (normal_distribution
// and friends) are not specified bit for bit and differ between library versions, so a seed
// would not reproduce the same files everywhere. Everything here is computed from the raw
// std::mt19937_64 output, whose sequence the standard does fix.
#include <cstdint>
#include <random>

#include "headingd/core/quaternion.hpp"

namespace headingd::sim {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  // An independent stream for one part of the simulation, so that drawing one more number
  // in, say, the GPS model does not shift every number the IMU model draws.
  static Rng stream(std::uint64_t seed, std::uint64_t stream_id);

  std::uint64_t raw() { return engine_(); }
  double uniform01();                    // [0, 1), 53 random bits
  double uniform(double lo, double hi);  // [lo, hi)
  double gaussian();                     // N(0, 1), Box-Muller
  core::Vec3 gaussian3() { return {gaussian(), gaussian(), gaussian()}; }
  core::Vec3 uniform3(double half_width) {
    return {uniform(-half_width, half_width), uniform(-half_width, half_width), uniform(-half_width, half_width)};
  }
  core::Vec3 unitVector();          // uniform on the sphere
  double exponential(double mean);  // waiting time of a Poisson process

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;  // Box-Muller yields two normals; the second is kept for the next call
  bool has_spare_ = false;
};

}  // namespace headingd::sim
