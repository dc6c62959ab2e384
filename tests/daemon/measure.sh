#!/usr/bin/env bash
# Measures the running daemon (a benchmark, not a pass/fail test): runs headingd on the
# bundled BROAD trial at real-time pace for a while, stops it with SIGTERM and prints tick
# jitter, processing time per tick, sample age at publish, message rates and resident memory.
# With --load N it keeps N CPU hogs busy for the run (the normal life of a small computer that
# also logs, records and serves) and stops them after.
#
# Usage: tests/daemon/measure.sh [--seconds N] [--speed X] [--rate HZ] [--publish WHEN] [--load N]
#                                [--fifo PRIO] [--driver-fifo PRIO] [--normal] [--cpu N]
#                                [--build DIR]
#   --seconds N          how long to run (default 30)
#   --speed X            play speed of the recording (default 1 = real time, 286 IMU samples/s)
#   --rate HZ            estimator rate (default 100)
#   --publish WHEN       [daemon] publish: tick (default) or imu
#   --load N             N busy-looping processes for the run (default 0), each at normal
#                        scheduling, stopped when the script ends (also on Ctrl-C)
#   --fifo PRIO          [realtime] sched_fifo_priority (default: the shipped default, 50)
#   --driver-fifo PRIO   [realtime] driver_fifo_priority (default: the shipped default, 55)
#   --normal             normal scheduling and pageable memory (both priorities 0,
#                        lock_memory = false): what was shipped before real time became the default
#   --cpu N              [realtime] cpu_affinity = [N]
#   --build DIR          build folder with daemon/headingd (default: build-daemon, else build)
# LCM goes to udpm with ttl=0 on a port of its own; in a private network namespace when
# permitted. Under SCHED_FIFO the daemon needs root (or CAP_SYS_NICE); otherwise it says so
# and the figures are those of normal scheduling.
set -euo pipefail
export LC_ALL=C
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
seconds=30 speed=1 rate=100 publish=tick load=0 fifo= driver_fifo= normal=0 cpu= build=
while [[ $# -gt 0 ]]; do
  case $1 in
    --seconds) seconds=$2; shift 2 ;;
    --speed) speed=$2; shift 2 ;;
    --rate) rate=$2; shift 2 ;;
    --load) load=$2; shift 2 ;;
    --publish) publish=$2; shift 2 ;;
    --fifo) fifo=$2; shift 2 ;;
    --driver-fifo) driver_fifo=$2; shift 2 ;;
    --normal) normal=1; shift ;;
    --cpu) cpu=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    -h|--help) sed -n '2,26s/^# \{0,1\}//p' "$0"; exit 0 ;;
    *) echo "measure.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
if [[ -z $build ]]; then
  for b in "$repo/build-daemon" "$repo/build"; do [[ -x $b/daemon/headingd ]] && { build=$b; break; }; done
fi
bin=$build/daemon/headingd
[[ -x $bin ]] || { echo "measure.sh: no headingd binary in ${build:-build-daemon or build}" >&2; exit 1; }

[[ $load =~ ^[0-9]+$ ]] || { echo "measure.sh: --load takes a number of processes" >&2; exit 2; }
# --normal: both priorities 0 unless --fifo or --driver-fifo say otherwise.
if ((normal)); then fifo=${fifo:-0} driver_fifo=${driver_fifo:-0}; fi

tmp=$(mktemp -d)
hogs=()
cleanup() {
  # Each hog by its own id; then reaped, so that none outlives the script.
  for p in "${hogs[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${hogs[@]}"; do wait "$p" 2>/dev/null || true; done
  rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 130' INT TERM
port=$((30000 + $$ % 20000))
cat >"$tmp/measure.toml" <<TOML
[daemon]
rate_hz = $rate
publish = "$publish"
[realtime]
cpu_affinity = [${cpu}]
$( [[ -n $fifo ]] && echo "sched_fifo_priority = $fifo" )
$( [[ -n $driver_fifo ]] && echo "driver_fifo_priority = $driver_fifo" )
$( ((normal)) && echo "lock_memory = false" )
[lcm]
url = "udpm://239.255.76.67:$port?ttl=0"
[imu_csv]
enabled = true
path = "$repo/config/demo/05_undisturbed_slow_rotation_with_breaks_B.csv.gz"
speed = $speed
at_end = "loop"
TOML

for ((i = 0; i < load; i++)); do
  sh -c 'while :; do :; done' &
  hogs+=($!)
done

run() {
  "$bin" --config "$tmp/measure.toml" 2>"$tmp/err" &
  pid=$!
  # Resident memory once a second while it runs; the highest is reported.
  rss_max=0
  for ((i = 0; i < seconds; i++)); do
    sleep 1
    rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$pid/status" 2>/dev/null || echo 0)
    ((rss > rss_max)) && rss_max=$rss
  done
  kill -TERM "$pid"
  wait "$pid"
  echo "$rss_max" >"$tmp/rss"
}
if unshare -n true 2>/dev/null; then
  export -f run; export bin tmp seconds
  unshare -n bash -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && run'
else
  run
fi

summary=$(grep -o 'summary {.*}' "$tmp/err" | tail -n 1 | sed 's/^summary //')
[[ -n $summary ]] || { echo "measure.sh: no summary from headingd:" >&2; cat "$tmp/err" >&2; exit 1; }
json() { printf '%s\n' "$summary" | sed -n "s/.*\"$1\":\([-0-9.e]*\).*/\1/p"; }
grep -E 'SCHED_FIFO|affinity|mlockall|memory locked|refused' "$tmp/err" | sed 's/^/  log: /' || true
sched="SCHED_FIFO ${fifo:-50} (drivers ${driver_fifo:-55}; 0 = normal scheduling) unless refused, memory $( ((normal)) && echo pageable || echo locked)"
ticks=$(json ticks)
cat <<REPORT
headingd on BROAD trial 05 at ${speed}x real time, estimator at $rate Hz (publish = $publish), ${seconds} s, $sched$( [[ -n $cpu ]] && echo ", on CPU $cpu"), $load CPU hog(s) on $(nproc) CPUs
  ticks                $ticks, deadline misses $(json deadline_misses)
  tick jitter          median $(json tick_jitter_p50_us) us, p99 $(json tick_jitter_p99_us) us, max $(json tick_jitter_max_us) us   (wake-up minus deadline)
  processing per tick  median $(json processing_p50_us) us, p99 $(json processing_p99_us) us, max $(json processing_max_us) us   (drain, estimate, queue the messages)
  sample age at publish median $(json sample_age_p50_us) us, p99 $(json sample_age_p99_us) us, max $(json sample_age_max_us) us   (newest IMU sample's arrival to its HEADING sent)
  messages             HEADING+ATTITUDE $(json heading_published), IMU $(json imu_published), STATUS $(json status_published), errors $(json publish_errors)
  rates                HEADING $(awk -v n="$(json heading_published)" -v s="$seconds" 'BEGIN { printf "%.1f", n / s }') Hz, IMU $(awk -v n="$(json imu_published)" -v s="$seconds" 'BEGIN { printf "%.1f", n / s }') Hz (over the ${seconds} s wall time, start-up included)
  resident memory      $(cat "$tmp/rss") kB while running (VmRSS, highest of 1 s samples); peak $(json max_rss_kb) kB (ru_maxrss)
REPORT
