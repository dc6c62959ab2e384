#!/usr/bin/env bash
# The README's main command: installs missing Debian packages (tools/scripts/install-deps.sh,
# a no-op when everything is present), builds the daemon into build/ with warnings as errors,
# and runs it on the bundled simulated capture (config/demo/, a 10 minute urban walk) at real
# time: LCM on this machine (udpm, ttl=0) and one status line a second on stdout. The daemon
# exits by itself at the end of the capture; Ctrl-C stops it earlier.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$repo"

tools/scripts/install-deps.sh
cmake -S . -B build -DHEADINGD_WERROR=ON >/dev/null
cmake --build build --target headingd -j"$(nproc)"
# The jar lcm-spy decodes the channels with (built only when a JDK is present).
if cmake --build build --target help | grep headingd_lcm_jar >/dev/null; then
  cmake --build build --target headingd_lcm_jar -j"$(nproc)" >/dev/null
fi

cat <<'TEXT'

headingd demo: 10 min simulated urban walk (config/demo/README.md), played at real time.
  Watch it:   tools/scripts/headingd-spy
  Record it:  lcm-logger --lcm-url='udpm://239.255.76.67:7667?ttl=0' demo.lcmlog
Each line: health | heading | declination (sources) | disturbance | message rates | timing

TEXT
exec build/daemon/headingd --config config/demo.toml
