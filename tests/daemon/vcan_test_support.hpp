#pragma once
// For the tests that drive the daemon's CAN source on vcan0 (run through vm-run.sh): their
// fixture, the shipped [can] table of headingd's own frame set pointed at vcan0, an IMU CSV
// turned into a candump log of those frames that canplayer plays onto the bus, and a simulated
// walk's inputs (that log and GPS epochs, written to a pty as a receiver sends them).
#include <gtest/gtest.h>
#include <net/if.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon_test_support.hpp"
#include "headingd/source_status_t.hpp"
#include "status_lookup.hpp"

namespace headingd::daemon::test {

// The fixture of the tests on vcan0, with a fresh folder each. CTest runs them inside
// tools/scripts/vm-run.sh (this host's kernel has no CAN); run by hand without vcan0, a test
// says so and is skipped instead of failing.
class OnVcan : public ::testing::Test {
 protected:
  void SetUp() override {
    if (if_nametoindex("vcan0") == 0) GTEST_SKIP() << "no vcan0: run through tools/scripts/vm-run.sh";
  }

  TempDir dir_;
};

// config/can-headingd.toml with interface vcan0 and an absolute DBC path; epoch_window_s stays
// as shipped (with counters the daemon's flush waits longer, drivers/can epoch_flush.hpp).
inline std::string vcanCanTable(const std::string& config_dir) {
  std::string table = readFile(config_dir + "/can-headingd.toml");
  table = std::regex_replace(table, std::regex("dbc = \"dbc/"), "dbc = \"" + config_dir + "/dbc/");
  return std::regex_replace(table, std::regex("interface = \"can0\""), "interface = \"vcan0\"");
}

// Writes `can_table` into dir/can.toml and `imu_csv` as dir/imu.log, a candump -l log.
inline void writeCandumpLog(const TempDir& dir, const std::string& candump_from_csv_bin, const std::string& can_table,
                            const std::string& imu_csv) {
  dir.write("can.toml", can_table);
  const std::string command = candump_from_csv_bin + " --imu-csv " + imu_csv + " --can-config " + dir.file("can.toml") +
                              " --out " + dir.file("imu.log") + " >/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

// The bytes of each GPS epoch (GGA, RMC, VTG, starting at GGA) of an NMEA capture, the
// first `count` (and one more, when there is one).
inline std::vector<std::string> nmeaEpochs(const std::string& nmea_path, std::size_t count) {
  std::vector<std::string> epochs;
  std::istringstream in(readFile(nmea_path));
  std::string line;
  while (std::getline(in, line) && epochs.size() <= count) {
    if (line.rfind("$GPGGA", 0) == 0) epochs.emplace_back();
    if (!epochs.empty()) epochs.back() += line + "\n";
  }
  return epochs;
}

// A simulated walk's inputs for the daemon: the [can] table for vcan0 and the GPS epochs.
struct SimulatedWalk {
  std::string can_table;
  std::vector<std::string> gps_epochs;
};

// headingd-sim's thesis-declination walk (seed 1; stand 10 s, walk north, ...) into dir/sim/
// (imu.csv, gps.nmea, truth.csv), its first `rows` IMU rows as dir/imu.csv and as the candump
// log dir/imu.log for vcan0 (writeCandumpLog). Returns the [can] table and the first
// `gps_epochs` epochs of its NMEA (nmeaEpochs).
inline SimulatedWalk simulatedWalkOnVcan(const TempDir& dir, const std::string& sim_bin, const std::string& candump_bin,
                                         const std::string& config_dir, int rows, std::size_t gps_epochs) {
  const std::string sim = sim_bin + " --scenario thesis-declination --seed 1 --cof " + config_dir +
                          "/wmm/WMM2025.COF --out-dir " + dir.file("sim") + " >/dev/null";
  EXPECT_EQ(std::system(sim.c_str()), 0) << sim;
  const std::string head =
      "head -n " + std::to_string(rows + 1) + " " + dir.file("sim/imu.csv") + " > " + dir.file("imu.csv");
  EXPECT_EQ(std::system(head.c_str()), 0) << head;
  const std::string can_table = vcanCanTable(config_dir);
  writeCandumpLog(dir, candump_bin, can_table, dir.file("imu.csv"));
  return {can_table, nmeaEpochs(dir.file("sim/gps.nmea"), gps_epochs)};
}

// Writes the first `count` epochs onto a GPS pty as a receiver sends them: epoch j at j s after
// the call, at `bytes_per_second` (the line rate).
template <class Pty>
void writeOneEpochPerSecond(Pty& gps, const std::vector<std::string>& epochs, int count, double bytes_per_second) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int j = 0; j < count; ++j) {
    std::this_thread::sleep_until(t0 + std::chrono::seconds(j));
    const std::string& e = epochs[static_cast<std::size_t>(j)];
    gps.writePaced({reinterpret_cast<const std::uint8_t*>(e.data()), e.size()}, bytes_per_second);
  }
}

// After canplayer has played the log: waits for the last samples and one more STATUS, stops
// the daemon with SIGTERM (it must exit 0 within `stop_timeout`), stops the subscriber and
// prints the daemon's summary line. Returns the daemon's log.
template <class Collector>
std::string finishVcanRun(const TempDir& dir, ChildProcess& daemon, Collector& lcm,
                          std::chrono::milliseconds stop_timeout) {
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  daemon.signal(SIGTERM);
  EXPECT_EQ(daemon.waitFor(stop_timeout), 0) << readFile(dir.file("err"));
  lcm.stop();
  const std::string log = readFile(dir.file("err"));
  const std::size_t summary = log.rfind("summary");
  std::fprintf(stderr, "%s", log.substr(summary == std::string::npos ? 0 : summary).c_str());
  return log;
}

}  // namespace headingd::daemon::test
