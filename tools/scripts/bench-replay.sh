#!/usr/bin/env bash
# Whole-process time and peak memory of headingd-replay against a plain VQF driver doing the
# same job on the same file: a BROAD trial as plain CSV in, one estimate row per sample out.
# The runs alternate (replay, VQF, replay, ...) so that both see the same machine; prints each
# run's wall time and peak RSS, the medians and the median of the pairwise ratios replay / VQF.
# Then headingd-replay's peak RSS on the trial and on the trial repeated 16 times (time shifted
# so that it keeps increasing): streaming keeps memory flat whatever the input's length.
#
# Usage: bench-replay.sh VQF_CPP_DIR [BUILD_DIR] [RUNS] [TRIAL]
#   VQF_CPP_DIR  the vqf/cpp folder of github.com/dlaidig/vqf (vqf.hpp, vqf.cpp; not bundled:
#                VQF is not a Debian package)
#   BUILD_DIR    headingd's build folder with tools/headingd-replay (default: build)
#   RUNS         pairs of runs (default 9)
#   TRIAL        a BROAD trial, gzip'd or plain (default: 01 of ../shared/data/broad, or
#                without ../shared trial 05 of tests/data/broad)
# Needs g++, python3 (the timer) and /usr/bin/time (Debian package time). The driver (tests/bench/vqf/vqf_csv_driver.cpp: std::getline, std::strtod, fprintf) and VQF
# are compiled -O2 -DNDEBUG, as headingd's default build (RelWithDebInfo) compiles headingd.
set -euo pipefail
vqf_dir=$1 build=${2:-build} runs=${3:-9} trial=${4:-}
here=$(cd "$(dirname "$0")/../.." && pwd)
if [[ -z $trial ]]; then
  trial="$here/../shared/data/broad/01_undisturbed_slow_rotation_A.csv.gz"
  [[ -f $trial ]] || trial="$here/tests/data/broad/05_undisturbed_slow_rotation_with_breaks_B.csv.gz"
fi
replay="$build/tools/headingd-replay"
[[ -x $replay ]] || { echo "bench-replay: no $replay (build the headingd-replay target)" >&2; exit 1; }
echo "trial: $trial"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -std=c++17 -O2 -g -DNDEBUG -I"$vqf_dir" "$here/tests/bench/vqf/vqf_csv_driver.cpp" "$vqf_dir/vqf.cpp" \
  -o "$work/vqf-csv-driver"
zcat -f "$trial" >"$work/plain.csv"  # plain CSV in: the comparison is of the tools, not of zlib
echo "rows: $(($(wc -l <"$work/plain.csv") - 1))"

# measure CMD...: prints "WALL_SECONDS PEAK_RSS_KB CPU_SECONDS" of one run: the wall time from
# a monotonic clock, the user + system time from the child's rusage (wait4), the peak RSS from
# /usr/bin/time (a small program: its own footprint before exec stays below the tool's).
# On a busy machine the wall time holds waits for a CPU, which weigh more on the shorter run:
# the CPU time shows the work alone.
measure() {
  python3 - "$work/rss" "$@" >"$work/measured" 2>"$work/stderr" <<'PYTHON' || { cat "$work/stderr" >&2; exit 1; }
import os, subprocess, sys, time
rss_file, command = sys.argv[1], sys.argv[2:]
start = time.monotonic()
child = subprocess.Popen(["/usr/bin/time", "-f", "%M", "-o", rss_file] + command,
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
_, status, usage = os.wait4(child.pid, 0)
wall = time.monotonic() - start
if status != 0:
    sys.stderr.write(child.stderr.read().decode())
    sys.exit(1)
rss = open(rss_file).read().split()[-1]
print(f"{wall:.4f} {rss} {usage.ru_utime + usage.ru_stime:.4f}")
PYTHON
  cat "$work/measured"
}

for ((i = 1; i <= runs; ++i)); do
  read -r rt rm rc < <(measure "$replay" --imu-csv "$work/plain.csv" --out "$work/replay.csv")
  read -r vt vm vc < <(measure "$work/vqf-csv-driver" "$work/plain.csv" "$work/vqf.csv")
  echo "run $i: headingd-replay $rt s $rm KB cpu $rc s, VQF driver $vt s $vm KB cpu $vc s"
done | tee "$work/runs"
awk '{ r[NR] = $4; v[NR] = $13; q[NR] = $4 / $13; rc[NR] = $9; vc[NR] = $18; qc[NR] = ($18 > 0 ? $9 / $18 : 0) }
  function median(a, n,   i, j, t) { for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
  END { printf "median wall time: headingd-replay %.4f s, VQF driver %.4f s; median of the pairwise ratios replay / VQF %.3f\n",
        median(r, NR), median(v, NR), median(q, NR)
        printf "median CPU time (user + system): headingd-replay %.4f s, VQF driver %.4f s; median of the pairwise ratios %.3f\n",
        median(rc, NR), median(vc, NR), median(qc, NR) }' "$work/runs"
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg) (on $(nproc) CPUs; wall times need an idle machine)"

# The trial 16 times over: each copy's times shifted by the previous copies' span plus one
# sample period, so time keeps increasing.
awk -F, -v OFS=, 'NR == FNR { if (FNR == 2) first = $1; if (FNR == 3) period = $1 - first; if (FNR > 1) last = $1; next }
  FNR == 1 { if (copy++ == 0) print; next }
  { $1 = sprintf("%.9g", $1 + (copy - 1) * (last - first + period)); print }' \
  "$work/plain.csv" $(for _ in $(seq 16); do echo "$work/plain.csv"; done) >"$work/plain16.csv"
read -r _ rss1 _ < <(measure "$replay" --imu-csv "$work/plain.csv" --out "$work/replay.csv")
read -r _ rss16 _ < <(measure "$replay" --imu-csv "$work/plain16.csv" --out "$work/replay16.csv")
echo "headingd-replay peak RSS: 1x $rss1 KB ($(($(wc -l <"$work/plain.csv") - 1)) rows), 16x $rss16 KB" \
  "($(($(wc -l <"$work/plain16.csv") - 1)) rows), 16x / 1x = $(awk -v a="$rss16" -v b="$rss1" 'BEGIN { printf "%.3f", a / b }')"
