#!/usr/bin/env bash
# Soak: runs headingd for MINUTES on the demo capture played in a loop at SPEED x real time
# (default 30 min at 20x: 10 simulated hours) and checks that nothing accumulates. Every
# SOAK_SAMPLE_S seconds (default 10) it samples the daemon's resident memory (VmRSS of
# /proc/PID/status); lcm-logger records every STATUS message (rings' high-water marks and
# drops, deadline misses, every source and estimator counter). At the end the two are joined
# into one CSV (a row per sample: time, RSS, the latest STATUS's fields) and it prints:
#   - RSS after the warm-up (the first SOAK_WARMUP_S seconds, default 120): min, max, spread
#     (must stay within +-1 MB, i.e. a spread of at most 2 MB);
#   - each ring's high-water mark at the end of the warm-up and at the end (must not grow);
#   - the counters of trouble (drops, misses, rejections, errors, time faults) that grew after
#     the warm-up: those drift (none expected).
# Exit status 0 when all three hold, 1 otherwise, 2 on bad usage or a missing tool.
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
daemon_pid= logger_pid=
cleanup() {
  [[ -n "$daemon_pid" ]] && kill "$daemon_pid" 2>/dev/null || true
  [[ -n "$logger_pid" ]] && kill "$logger_pid" 2>/dev/null || true
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
"$export_tool" "$work/status.lcm" --out-dir "$out" --channel STATUS >/dev/null

python3 - "$out/rss.csv" "$out/STATUS.csv" "$out/soak.csv" "$warmup_s" "$speed" <<'PY'
import csv, re, sys

rss_path, status_path, out_path, warmup_s, speed = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
rss = list(csv.DictReader(open(rss_path)))
status = list(csv.DictReader(open(status_path)))
if not rss or not status:
    sys.exit("soak: no samples or no STATUS messages")

# The fields worth following: ticks and misses, every ring's figures, every counter.
def followed(name):
    return name in ("state", "ticks", "deadline_misses", "publish_errors", "heading_rate_hz", "imu_rate_hz") or \
        name.startswith("rings.") or name.startswith("counters.") or \
        (name.startswith("sources.") and (".counters." in name or name.endswith(".state")))
columns = [c for c in status[0].keys() if followed(c)]

# Each RSS sample with the latest STATUS received at or before it.
rows, j = [], -1
for r in rss:
    t = int(r["utime_us"])
    while j + 1 < len(status) and int(status[j + 1]["log_utime"]) <= t:
        j += 1
    if j >= 0:
        rows.append([r["t_s"], r["rss_kb"]] + [status[j][c] for c in columns])
with open(out_path, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["t_s", "rss_kb"] + columns)
    w.writerows(rows)

def num(x):
    try:
        return float(x)
    except ValueError:
        return None

after = [r for r in rows if float(r[0]) >= warmup_s]
if len(after) < 2:
    sys.exit(f"soak: fewer than two samples after the {warmup_s:.0f} s warm-up")
ok = True
idx = {c: i + 2 for i, c in enumerate(columns)}

# RSS after the warm-up.
rss_kb = [int(r[1]) for r in after]
spread = max(rss_kb) - min(rss_kb)
first, last = rss_kb[0], rss_kb[-1]
run_s = float(rows[-1][0])
print(f"soak: {run_s / 60:.1f} min at {speed:g}x = {run_s * speed / 3600:.2f} simulated hours; {len(rows)} samples, "
      f"{len(status)} STATUS messages")
print(f"RSS after the {warmup_s:.0f} s warm-up: min {min(rss_kb) / 1024:.2f} MB, max {max(rss_kb) / 1024:.2f} MB, "
      f"spread {spread / 1024:.2f} MB (first {first / 1024:.2f}, last {last / 1024:.2f} MB; whole run from "
      f"{int(rows[0][1]) / 1024:.2f} MB)")
quarters = [after[int(k * (len(after) - 1) / 4)] for k in range(5)]
print("RSS curve (MB at t s): " + ", ".join(f"{int(r[1]) / 1024:.2f} at {float(r[0]):.0f}" for r in quarters))
if spread > 2048:
    ok = False
    print("  FAIL: RSS not flat within +-1 MB")

# High-water marks: at the end of the warm-up and at the end.
for c in columns:
    if c.startswith("rings.") and c.endswith(".high_water"):
        a, b = num(after[0][idx[c]]), num(after[-1][idx[c]])
        cap = num(after[-1][idx[c.replace(".high_water", ".capacity")]]) if c.replace(".high_water", ".capacity") in idx else None
        grew = a is not None and b is not None and b > a
        print(f"{c}: {a:.0f} after warm-up, {b:.0f} at the end (capacity {cap:.0f})" + ("  GREW" if grew else ""))
        ok = ok and not grew
        # Where it rose: the STATUS window of each rise, with that window's latest tick (a ring
        # drained late holds what arrived meanwhile) and its IMU rate. A rise that the late tick
        # does not explain would be a backlog building up.
        warm_end_us = int(status[0]["log_utime"]) + warmup_s * 1e6
        level = a
        for m in status:
            hw = num(m.get(c, ""))
            if hw is None or int(m["log_utime"]) < warm_end_us or hw <= level:
                continue
            late_ms = num(m["tick_jitter_max_us"]) / 1000
            arrived = num(m["imu_rate_hz"]) * late_ms / 1000
            t_s = (int(m["log_utime"]) - int(status[0]["log_utime"])) / 1e6
            print(f"  rose {level:.0f} -> {hw:.0f} at {t_s:.0f} s, in a window whose latest tick woke {late_ms:.1f} ms "
                  f"late ({arrived:.0f} IMU samples arrive in that time; deadline misses so far {m['deadline_misses']})")
            level = hw

# Counters of trouble that grew after the warm-up; the others are progress and are listed
# with their growth per simulated hour for reference.
trouble = re.compile(r"drop|miss|error|reject|backward|duplicate|jump|gap|forced|bad|lost|overflow|incomplete|late|"
                     r"non_finite|out_of_range|truncat|busy|disconnect|without_time|not_placed|recover")
drifting, progress = [], []
sim_hours = (float(after[-1][0]) - float(after[0][0])) * speed / 3600
for c in columns:
    if not (c.startswith("counters.") or ".counters." in c or c in ("deadline_misses", "publish_errors")):
        continue
    if c.endswith(".name"):
        continue
    a, b = num(after[0][idx[c]]), num(after[-1][idx[c]])
    if a is None or b is None:
        continue
    name = c.split(".")[-1] if not c.endswith(".value") else c.split(".")[-2]
    if trouble.search(c):
        if b > a:
            share = ""
            if c == "deadline_misses":  # a share of the ticks: load on the machine shows here
                ticks = num(after[-1][idx["ticks"]]) - num(after[0][idx["ticks"]])
                share = f" ({100 * (b - a) / max(ticks, 1):.2f} % of the {ticks:.0f} ticks)"
            drifting.append(f"{c}: {a:.0f} -> {b:.0f}{share}")
    elif b > a and sim_hours > 0:
        progress.append(f"{c} +{(b - a) / sim_hours:.0f}/h")
print("counters of trouble that grew after the warm-up: " + ("; ".join(drifting) if drifting else "none"))
print("progress counters (growth per simulated hour): " + "; ".join(progress))
ok = ok and not drifting
print(f"soak: {'PASS' if ok else 'FAIL'}; table: {out_path}")
sys.exit(0 if ok else 1)
PY
