// The daemon's configuration (TOML): parseDaemonConfig on arbitrary text, with relative paths
// taken from the repository's config/ folder so the seeds' DBC and WMM files are found and
// read (the [can] and [candump_log] tables parse their DBC). Invariant: only ConfigError is
// thrown, the error the daemon and --check-config report as "bad configuration".
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "headingd/daemon/config/config.hpp"

using namespace headingd;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const daemon::DaemonConfig config = daemon::parseDaemonConfig(text, "fuzz.toml", HEADINGD_FUZZ_CONFIG_DIR);
    FUZZ_CHECK(config.rate_hz >= 1.0 && config.rate_hz <= 2000.0);
    FUZZ_CHECK(config.imu_ring_capacity >= 16 && config.gps_ring_capacity >= 4);
  } catch (const core::ConfigError&) {
  }
  return 0;
}
