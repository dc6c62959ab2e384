// headingd-replay: runs the estimator over a recorded IMU CSV as fast as the CPU allows and
// writes one estimate per input row.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>

#include "headingd/core/estimator.hpp"
#include "headingd/core/params_toml.hpp"
#include "headingd/replay/imu_csv.hpp"
#include "headingd/replay/numeric_csv.hpp"

namespace {

using namespace headingd;

core::EstimatorParams loadParams(const std::string& path) {
  if (path.empty()) return {};
  return core::parseEstimatorParams(replay::readMaybeGzipFile(path), path);
}

void printCounters(const core::EstimatorCounters& c, std::size_t rows, double seconds) {
  const auto& s = c.samples;
  std::fprintf(stderr,
               "{\"rows\":%zu,\"accepted\":%llu,\"gaps\":%llu,\"clock_jumps\":%llu,\"duplicate_time\":%llu,"
               "\"backwards_time\":%llu,\"non_finite\":%llu,\"non_finite_mag\":%llu,\"backtracks\":%llu,"
               "\"mag_no_heading\":%llu,\"state_recoveries\":%llu,\"estimator_ns_per_sample\":%.1f}\n",
               rows, static_cast<unsigned long long>(s.accepted), static_cast<unsigned long long>(s.gaps),
               static_cast<unsigned long long>(s.clock_jumps), static_cast<unsigned long long>(s.duplicate_time),
               static_cast<unsigned long long>(s.backwards_time), static_cast<unsigned long long>(s.non_finite),
               static_cast<unsigned long long>(s.non_finite_mag), static_cast<unsigned long long>(c.backtracks),
               static_cast<unsigned long long>(c.mag_no_heading),
               static_cast<unsigned long long>(c.state_recoveries), rows ? seconds * 1e9 / rows : 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Replay an IMU CSV (BROAD format, plain or gzip) through the headingd estimator."};
  std::string imu_csv, config, out;
  app.add_option("--imu-csv", imu_csv, "IMU CSV: header t,gyr_x..z [rad/s],acc_x..z [m/s^2],mag_x..z [uT]")
      ->required();
  app.add_option("--config", config, "TOML file with an [estimator] table (config/estimator.toml lists the keys)");
  app.add_option("--out", out, "output CSV: t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg")->required();
  CLI11_PARSE(app, argc, argv);

  try {
    const core::EstimatorParams params = loadParams(config);
    const auto samples = replay::readImuCsv(imu_csv);
    core::Estimator estimator(params);

    // Estimates are kept in memory and written afterwards, so the timing below is the
    // estimator's alone.
    std::vector<core::EstimatorOutput> estimates(samples.size());
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      estimator.process(samples[i]);
      estimates[i] = estimator.output();  // a rejected sample repeats the last estimate
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::FILE* f = std::fopen(out.c_str(), "w");
    if (f == nullptr) throw std::runtime_error(out + ": cannot open for writing");
    std::fputs("t,qw,qx,qy,qz,roll_deg,pitch_deg,yaw_deg\n", f);
    constexpr double kDeg = 180.0 / std::numbers::pi;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const auto& e = estimates[i];
      const double t = static_cast<double>(samples[i].t_ns) * 1e-9;
      if (!e.valid) {  // nothing usable yet: say so rather than invent an attitude
        std::fprintf(f, "%.9g,nan,nan,nan,nan,nan,nan,nan\n", t);
        continue;
      }
      std::fprintf(f, "%.9g,%.9f,%.9f,%.9f,%.9f,%.6f,%.6f,%.6f\n", t, e.q_nb.w(), e.q_nb.x(), e.q_nb.y(),
                   e.q_nb.z(), e.euler.roll_rad * kDeg, e.euler.pitch_rad * kDeg, e.euler.yaw_rad * kDeg);
    }
    if (std::fclose(f) != 0) throw std::runtime_error(out + ": write failed");
    printCounters(estimator.counters(), samples.size(), seconds);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-replay: %s\n", e.what());
    return 1;
  }
  return 0;
}
