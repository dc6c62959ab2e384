#!/usr/bin/env bash
# Soak: runs headingd for MINUTES on the demo capture played in a loop at SPEED x real time
# (default 30 min at 20x: 10 simulated hours) and checks that nothing accumulates. Every
# SOAK_SAMPLE_S seconds (default 10) it samples the daemon's resident memory (VmRSS of
# /proc/PID/status); lcm-logger records every STATUS message (rings' high-water marks and
# drops, deadline misses, every source and estimator counter); stall-probe.py writes down
# each moment the machine could not run even a SCHED_FIFO 99 thread for 2 ms or more. At the
# end soak-verdict.py joins them into one CSV and judges the run: RSS flat after the warm-up
# (+-1 MB), no backlog building up in any ring, and every rise of a ring's high-water mark
# and every deadline miss coming with time the machine took (soak-verdict.py says how); no
# other counter of trouble growing.
# Exit status 0 when all hold, 1 otherwise, 2 on bad usage or a missing tool.
#
# The demo capture (config/demo: the candump log of the CAN IMU frames and the NMEA log) is
# played as the demo plays it, by [candump_log] and [nmea_log] through the CAN decoder, the
# epoch assembler and the NMEA player, with [playback] at_end = "loop": each loop later on
# the log axis by the capture's length plus one sample period.
#
# usage: tools/scripts/soak.sh [MINUTES] [SPEED]        (defaults 30 and 20)
# environment: SOAK_BUILD (build tree, default build), SOAK_OUT (folder for soak.csv, the
#   STATUS table and the daemon's log; default a new folder under /tmp), SOAK_SAMPLE_S,
#   SOAK_WARMUP_S. Run it under `nice` on a shared machine.
set -euo pipefail
export LC_ALL=C

minutes=${1:-30}
speed=${2:-20}
[[ "$minutes" =~ ^[0-9]+([.][0-9]+)?$ && "$speed" =~ ^[0-9]+([.][0-9]+)?$ ]] || {
  echo "usage: soak.sh [MINUTES] [SPEED]" >&2
  exit 2
}
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${SOAK_BUILD:-$repo/build}
sample_s=${SOAK_SAMPLE_S:-10}
warmup_s=${SOAK_WARMUP_S:-120}
out=${SOAK_OUT:-$(mktemp -d "${TMPDIR:-/tmp}/headingd-soak.XXXXXX")}
mkdir -p "$out"

headingd=$build/daemon/headingd
export_tool=$build/tools/lcm_export/headingd-lcm-export
for tool in "$headingd" "$export_tool"; do
  [[ -x "$tool" ]] || { echo "soak: $tool is not built (cmake --build $build --target $(basename "$tool"))" >&2; exit 2; }
done
command -v lcm-logger >/dev/null || { echo "soak: lcm-logger missing (apt-get install liblcm-bin)" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/headingd-soak-work.XXXXXX")
daemon_pid= logger_pid= probe_pid=
cleanup() {
  [[ -n "$daemon_pid" ]] && kill "$daemon_pid" 2>/dev/null || true
  [[ -n "$logger_pid" ]] && kill "$logger_pid" 2>/dev/null || true
  [[ -n "$probe_pid" ]] && kill "$probe_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

# A port of its own, ttl=0: nothing leaves the machine, other runs do not mix in.
url="udpm://239.255.76.67:$((30000 + $$ % 20000))?ttl=0"
cat >"$work/soak.toml" <<TOML
[daemon]
rate_hz = 100.0
wmm = "$repo/config/wmm/WMM2025.COF"
[lcm]
url = "$url"
[playback]
speed = $speed
at_end = "loop"
[candump_log]
enabled = true
path = "$repo/config/demo/sim-urban-walk-can.log.gz"
can_config = "$repo/config/can-headingd.toml"
[nmea_log]
enabled = true
path = "$repo/config/demo/sim-urban-walk.nmea"
[recorder]
enabled = false
TOML

lcm-logger --quiet --channel=STATUS --lcm-url="$url" "$work/status.lcm" >/dev/null &
logger_pid=$!
# The machine's own stalls, to tell them from the daemon's (stall-probe.py).
"$repo/tools/scripts/stall-probe.py" "$out/stalls.csv" 2 &
probe_pid=$!
sleep 0.5
"$headingd" --config "$work/soak.toml" >"$out/headingd.out" 2>"$out/headingd.log" &
daemon_pid=$!

total_s=$(awk -v m="$minutes" 'BEGIN { printf "%d", m * 60 }')
echo "soak: headingd (pid $daemon_pid) at ${speed}x for $minutes min; samples every ${sample_s} s into $out/rss.csv" >&2
echo "t_s,utime_us,rss_kb" >"$out/rss.csv"
start=$(date +%s%N)
while :; do
  now=$(date +%s%N)
  elapsed_ms=$(((now - start) / 1000000))
  ((elapsed_ms >= total_s * 1000)) && break
  if ! rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$daemon_pid/status" 2>/dev/null); then
    echo "soak: headingd exited early; its log: $out/headingd.log" >&2
    daemon_pid=
    exit 1
  fi
  echo "$((elapsed_ms / 1000)).$(printf '%03d' $((elapsed_ms % 1000))),$((now / 1000)),$rss" >>"$out/rss.csv"
  sleep "$sample_s"
done
kill -TERM "$daemon_pid"
wait "$daemon_pid" || { echo "soak: headingd exited with status $?; its log: $out/headingd.log" >&2; exit 1; }
daemon_pid=
sleep 1
kill -INT "$logger_pid"
wait "$logger_pid" || true
logger_pid=
kill -TERM "$probe_pid"
wait "$probe_pid" || true
probe_pid=
"$export_tool" "$work/status.lcm" --out-dir "$out" --channel STATUS >/dev/null

python3 "$repo/tools/scripts/soak-verdict.py" "$out" "$warmup_s" "$speed"
