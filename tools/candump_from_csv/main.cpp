// headingd-candump-from-csv: IMU CSV -> candump -l log, through the DBC encoder of a [can]
// configuration. The log plays onto a bus with `canplayer` and replays through headingd.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "headingd/can/candump_writer.hpp"
#include "headingd/cli/parse_command_line.hpp"
#include "headingd/files/imu_csv.hpp"
#include "headingd/files/numeric_csv.hpp"
#include "headingd/files/output_file.hpp"

int main(int argc, char** argv) {
  using namespace headingd;
  CLI::App app{"Convert an IMU CSV (BROAD format) into a candump -l log of the IMU's CAN frames."};
  std::string imu_csv, can_config, out_path, interface;
  double start_time_s = 1700000000.0, frame_spacing_us = 200.0;
  int mag_every = 1;
  app.add_option("--imu-csv", imu_csv, "IMU CSV: t [s], gyr_x..z [rad/s], acc_x..z [m/s^2], mag_x..z [uT]")->required();
  app.add_option("--can-config", can_config, "TOML file with a [can] table (e.g. config/can-headingd.toml)")
      ->required();
  app.add_option("--out", out_path, "candump -l log to write")->required();
  app.add_option("--interface", interface, "interface name in the log (default: [can] interface)");
  app.add_option("--start-time", start_time_s, "UNIX time [s] of CSV time 0")->capture_default_str();
  app.add_option("--frame-spacing-us", frame_spacing_us, "time between the frames of one epoch [us]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100000.0));
  app.add_option("--mag-every", mag_every, "write magnetometer frames on every n-th epoch only")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  app.footer(
      std::string("Exit codes: 0 written, 1 an input cannot be read or is malformed, or --out cannot be written, 2 bad "
                  "arguments (also an --out that is an input). --out is written to a temporary file in its folder and "
                  "renamed into place when complete.") +
      "\n" + headingd::cli::kFileRules);
  if (const auto status = headingd::cli::parseCommandLine(app, argc, argv)) return *status;

  try {
    files::refuseOutputOverInputs({"--out", out_path}, {{"--imu-csv", imu_csv}, {"--can-config", can_config}});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-candump-from-csv: %s\n", e.what());
    return cli::kExitBadArguments;
  }
  try {
    const can::CanSetup setup = can::loadCanSetup(can_config);
    const can::ImuFrameCodec codec(setup.config, setup.dbc);
    const auto samples = files::readImuCsv(imu_csv);
    can::CandumpWriteOptions options;
    options.interface = interface.empty() ? setup.config.interface : interface;
    options.start_time_ns = std::llround(start_time_s * 1e9);
    options.frame_spacing_ns = std::llround(frame_spacing_us * 1e3);
    options.mag_every = mag_every;
    const double epoch_span_s = frame_spacing_us * 1e-6 * static_cast<double>(codec.messages().size() - 1);
    if (codec.sequenceBits() == 0 && epoch_span_s > setup.config.epoch_window_s) {
      std::fprintf(stderr,
                   "warning: the frames of one epoch span %.6f s, more than epoch_window_s = %.6f s of %s; "
                   "a receiver without counters will split epochs\n",
                   epoch_span_s, setup.config.epoch_window_s, can_config.c_str());
    }
    // Through a temporary file renamed into place (files/output_file.hpp).
    std::ostringstream out;
    const can::CandumpWriteStats stats = can::writeCandumpLog(samples, codec, options, out);
    files::writeWholeOutputFile(out_path, out.str());
    std::fprintf(stdout, "{\"rows\":%zu,\"epochs\":%llu,\"frames\":%llu,\"clamped_values\":%llu}\n", samples.size(),
                 static_cast<unsigned long long>(stats.epochs), static_cast<unsigned long long>(stats.frames),
                 static_cast<unsigned long long>(stats.clamped_values));
    if (stats.clamped_values > 0) {
      std::fprintf(stderr, "warning: %llu values exceeded the DBC signal ranges and were clamped\n",
                   static_cast<unsigned long long>(stats.clamped_values));
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "headingd-candump-from-csv: %s\n", e.what());
    return 1;
  }
}
