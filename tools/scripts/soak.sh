#!/usr/bin/env bash
# Soak: runs headingd for MINUTES on the demo capture played in a loop at SPEED x real time
# (default 30 min at 20x: 10 simulated hours) and checks that nothing accumulates. Every
# SOAK_SAMPLE_S seconds (default 10) it samples the daemon's resident memory (VmRSS of
# /proc/PID/status); lcm-logger records every STATUS message (rings' high-water marks and
# drops, deadline misses, every source and estimator counter); stall-probe.py writes down
# each moment the machine could not run even a SCHED_FIFO 99 thread for 2 ms or more. At the
# end the two are joined into one CSV (a row per sample: time, RSS, the latest STATUS's
# fields) and it prints:
#   - RSS after the warm-up (the first SOAK_WARMUP_S seconds, default 120): min, max, spread
#     (must stay within +-1 MB, i.e. a spread of at most 2 MB);
#   - the machine's stalls seen by the probe;
#   - each ring's high-water mark at the end of the warm-up and at the end, and each rise:
#     a rise must come with a stall of the machine (the probe saw at least half the time the
#     ring's content took to arrive beyond one tick period, in that STATUS window or the one
#     before); and each ring's window_high_water (most waiting at a tick, per STATUS window)
#     in each third of the run: its median must not grow (by more than 25 % and 3 samples),
#     which a backlog building up would do;
#   - the counters of trouble (drops, misses, rejections, errors, time faults) that grew after
#     the warm-up: those drift (none expected), except deadline misses that each come with a
#     stall of the machine as long as the tick's lateness (at least half of it, as above).
# Without the right to real-time scheduling the probe cannot tell a stall of the machine from
# one of the scheduler, and no stall excuses anything.
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

python3 - "$out/rss.csv" "$out/STATUS.csv" "$out/soak.csv" "$warmup_s" "$speed" "$out/stalls.csv" <<'PY'
import bisect, csv, re, statistics, sys

rss_path, status_path, out_path, warmup_s, speed = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
stalls_path = sys.argv[6]
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

# The machine's stalls (stall-probe.py): when even a SCHED_FIFO 99 thread could not run.
probe_lines = open(stalls_path).read().splitlines()
probe_rt = not (probe_lines and probe_lines[0].startswith("# not real-time"))
stalls = sorted((int(r["wall_utime_us"]), float(r["late_ms"]))
                for r in csv.DictReader(l for l in probe_lines if not l.startswith("#")))
stall_t = [t for t, _ in stalls]
warm_end_us = int(status[0]["log_utime"]) + warmup_s * 1e6
period_ms = 1000 / num(status[-1]["rate_hz"])

def stall_in_window(k):
    """The longest stall the probe saw in STATUS window k or the one before it (ms)."""
    lo = int(status[k - 2]["log_utime"]) if k >= 2 else 0
    hi = int(status[k]["log_utime"])
    return max((ms for _, ms in stalls[bisect.bisect_right(stall_t, lo):bisect.bisect_right(stall_t, hi)]), default=0.0)

def host_stall(k, needed_ms):
    """True when the probe saw a stall at least half of `needed_ms` (its 1 ms sleeps and the
    two threads' stalls adding up leave that margin) around window k: the machine's doing."""
    seen = stall_in_window(k)
    return probe_rt and seen >= max(2.0, 0.5 * needed_ms), seen

windows = [k for k, m in enumerate(status) if int(m["log_utime"]) >= warm_end_us]
long_stalls = [ms for t, ms in stalls if t >= warm_end_us]
print(f"machine stalls after the warm-up (stall-probe.py{'' if probe_rt else ', NOT real-time: no stall excuses anything'}): "
      f"{len(long_stalls)} of 2 ms or more, {sum(ms >= 10 for ms in long_stalls)} of 10 ms or more, longest "
      f"{max(long_stalls, default=0):.1f} ms; in {sum(stall_in_window(k) >= 2 for k in windows)} of {len(windows)} STATUS windows "
      f"(a window and the one before it)")

# Rings. high_water is the most ever waiting, so it also keeps the worst stall the machine
# ever dealt the daemon; a backlog building up shows in window_high_water (most waiting at a
# tick in each STATUS window) rising from the first to the last third of the run.
for c in columns:
    if c.startswith("rings.") and c.endswith(".high_water"):
        a, b = num(after[0][idx[c]]), num(after[-1][idx[c]])
        cap = num(after[-1][idx[c.replace(".high_water", ".capacity")]])
        print(f"{c}: {a:.0f} after warm-up, {b:.0f} at the end (capacity {cap:.0f})" + ("  GREW" if b > a else ""))
        # Each rise, with its window's latest tick (a ring drained late holds what arrived
        # meanwhile) and what the probe saw: time the ring's content took to arrive beyond one
        # tick period must have been a stall of the machine.
        level = a
        for k in windows:
            m = status[k]
            hw = num(m.get(c, ""))
            if hw is None or hw <= level:
                continue
            late_ms = num(m["tick_jitter_max_us"]) / 1000
            rate = max(num(m["imu_rate_hz"]), 1.0)
            needed_ms = 1000 * hw / rate - period_ms
            host, seen = host_stall(k, needed_ms)
            t_s = (int(m["log_utime"]) - int(status[0]["log_utime"])) / 1e6
            print(f"  rose {level:.0f} -> {hw:.0f} at {t_s:.0f} s: {hw:.0f} samples are {1000 * hw / rate:.1f} ms of data; "
                  f"latest tick {late_ms:.1f} ms late; the probe saw a {seen:.1f} ms stall: "
                  + ("the machine's" if host else "NOT EXPLAINED by a stall of the machine"))
            ok = ok and host
            level = hw
        wc = c.replace(".high_water", ".window_high_water")
        if wc not in status[0]:
            continue
        peaks = [num(status[k][wc]) for k in windows if num(status[k][wc]) is not None]
        thirds = [peaks[i * len(peaks) // 3:(i + 1) * len(peaks) // 3] for i in range(3)]
        if min(len(t) for t in thirds) == 0:
            continue
        def fig(t):
            t = sorted(t)
            return f"median {statistics.median(t):.0f}, p99 {t[min(len(t) - 1, int(0.99 * len(t)))]:.0f}, max {t[-1]:.0f}"
        print(f"  {wc} in each third after the warm-up: " + "; ".join(fig(t) for t in thirds))
        first_median, last_median = statistics.median(thirds[0]), statistics.median(thirds[2])
        if last_median > max(first_median * 1.25, first_median + 3):
            ok = False
            print(f"  FAIL: a backlog builds up (median {first_median:.0f} -> {last_median:.0f})")

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
                # A miss is a tick held off for about a period: each window with one must have
                # had a stall of the machine that long.
                unexplained = [k for k in windows if num(status[k]["deadline_misses"]) > num(status[k - 1]["deadline_misses"])
                               and not host_stall(k, max(period_ms, num(status[k]["tick_jitter_max_us"]) / 1000))[0]]
                share += f"; in windows without a stall of the machine: {len(unexplained)}"
                if not unexplained:
                    print(f"{c}: {a:.0f} -> {b:.0f}{share}: each with a stall of the machine")
                    continue
            drifting.append(f"{c}: {a:.0f} -> {b:.0f}{share}")
    elif b > a and sim_hours > 0:
        progress.append(f"{c} +{(b - a) / sim_hours:.0f}/h")
print("counters of trouble that grew after the warm-up: " + ("; ".join(drifting) if drifting else "none"))
print("progress counters (growth per simulated hour): " + "; ".join(progress))
ok = ok and not drifting
print(f"soak: {'PASS' if ok else 'FAIL'}; table: {out_path}")
sys.exit(0 if ok else 1)
PY
