#!/usr/bin/env python3
"""The soak's verdict (soak.sh runs it at the end; run it again on a soak's folder to judge an
earlier run): from DIR/rss.csv (the daemon's VmRSS every few seconds), DIR/STATUS.csv (every
STATUS, exported by headingd-lcm-export) and DIR/stalls.csv (stall-probe.py: each moment the
machine could not run even a SCHED_FIFO 99 thread for 2 ms or more) it writes DIR/soak.csv,
one row per RSS sample with the latest STATUS's fields, and prints:
  - RSS after the warm-up: min, max, spread (must stay within +-1 MB: a spread of 2 MB);
  - the machine's stalls;
  - each ring's high-water mark at the end of the warm-up and at the end, and each rise: a
    rise must come with time the machine took (below) of at least half the time the ring's
    content took to arrive beyond one tick period; and each ring's window_high_water (most
    waiting at a tick, per STATUS window) in each third of the run: its median must not
    grow (by more than 25 % and 3 samples), which a backlog building up would do;
  - the counters of trouble (drops, misses, rejections, errors, time faults) that grew after
    the warm-up: none may, except deadline misses that each come with time the machine took
    of at least half the tick's lateness (and of half a period).
Time the machine took, around a STATUS window (that window and the one before it): the most
that one CPU's probe lost within any 100 ms, summed over its late wakes. A stall often comes
as a train (a few ms lost, 1 ms run, a few ms lost, ...), which delays a thread by the sum.
Without the right to real-time scheduling the probe cannot tell a stall of the machine from
one of the scheduler, and no stall excuses anything.

usage: soak-verdict.py DIR [WARMUP_S] [SPEED]      (defaults 120 and 20, as soak.sh)
Exit status 0 when every check holds, 1 otherwise.
"""
import bisect, csv, re, statistics, sys

if not 2 <= len(sys.argv) <= 4:
    sys.exit(__doc__)
folder = sys.argv[1]
warmup_s = float(sys.argv[2]) if len(sys.argv) > 2 else 120.0
speed = float(sys.argv[3]) if len(sys.argv) > 3 else 20.0
rss_path, status_path, out_path, stalls_path = (f"{folder}/{name}" for name in ("rss.csv", "STATUS.csv", "soak.csv", "stalls.csv"))
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
stall_rows = [(int(r["wall_utime_us"]), r["cpu"], float(r["late_ms"]))
              for r in csv.DictReader(l for l in probe_lines if not l.startswith("#"))]
warm_end_us = int(status[0]["log_utime"]) + warmup_s * 1e6
period_ms = 1000 / num(status[-1]["rate_hz"])
TRAIN_US = 100_000

# Per CPU: each late wake's time and the time lost in the 100 ms up to it (a train's sum).
by_cpu = {}
for r in stall_rows:
    by_cpu.setdefault(r[1], []).append((r[0], r[2]))
trains = []  # (time, ms lost in the 100 ms up to it), all CPUs
for events in by_cpu.values():
    events.sort()
    oldest, lost = 0, 0.0  # the first wake within the span, and the sum since it
    for t, ms in events:
        lost += ms
        while events[oldest][0] < t - TRAIN_US:
            lost -= events[oldest][1]
            oldest += 1
        trains.append((t, lost))
trains.sort()
train_t = [t for t, _ in trains]

def lost_around(k):
    """The most time the machine took from one CPU within 100 ms, in STATUS window k or the one
    before it (ms)."""
    lo = int(status[k - 2]["log_utime"]) if k >= 2 else 0
    hi = int(status[k]["log_utime"])
    return max((ms for _, ms in trains[bisect.bisect_right(train_t, lo):bisect.bisect_right(train_t, hi)]), default=0.0)

def host_stall(k, needed_ms):
    """True when the machine took at least half of `needed_ms` (the probe's 1 ms sleeps and two
    threads' stalls adding up leave that margin) around window k: the machine's doing."""
    seen = lost_around(k)
    return probe_rt and seen >= max(2.0, 0.5 * needed_ms), seen

windows = [k for k, m in enumerate(status) if int(m["log_utime"]) >= warm_end_us]
late_wakes = [ms for t, _, ms in stall_rows if t >= warm_end_us]
half_period = sum(lost_around(k) >= max(2.0, 0.5 * period_ms) for k in windows)
print(f"machine stalls after the warm-up (stall-probe.py{'' if probe_rt else ', NOT real-time: no stall excuses anything'}): "
      f"{len(late_wakes)} wakes 2 ms or more late, {sum(ms >= 10 for ms in late_wakes)} of them 10 ms or more, the "
      f"longest {max(late_wakes, default=0):.1f} ms; {half_period} of {len(windows)} STATUS windows lost half a tick period "
      f"({0.5 * period_ms:.1f} ms) or more within 100 ms on a CPU (around the window: it and the one before)")

def peak_figures(peaks):
    t = sorted(peaks)
    return f"median {statistics.median(t):.0f}, p99 {t[min(len(t) - 1, int(0.99 * len(t)))]:.0f}, max {t[-1]:.0f}"

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
                  f"latest tick {late_ms:.1f} ms late; the machine took {seen:.1f} ms from a CPU within 100 ms: "
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
        print(f"  {wc} in each third after the warm-up: " + "; ".join(peak_figures(t) for t in thirds))
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
