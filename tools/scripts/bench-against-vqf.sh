#!/usr/bin/env bash
# Cost per sample of headingd's estimator against VQF's 9D filter on the same BROAD trial,
# run in turn so that both see the same machine: prints each run's time_per_sample and the
# medians and the median of the pairwise ratios headingd / VQF.
#
# Usage: bench-against-vqf.sh VQF_CPP_DIR [BUILD_DIR] [RUNS]
#   VQF_CPP_DIR  the vqf/cpp folder of a checkout of github.com/dlaidig/vqf (not bundled:
#                VQF is not a Debian package), e.g. after
#                git clone https://github.com/dlaidig/vqf /tmp/vqf  ->  /tmp/vqf/vqf/cpp
#   BUILD_DIR    headingd's build folder with tests/headingd-bench (default: build)
#   RUNS         pairs of runs (default 9)
# VQF is compiled with the flags of headingd's default build (-O2, RelWithDebInfo).
# The trial is headingd-bench's: 01 of ../shared/data/broad, or without ../shared trial 05 of
# the repository's tests/data/broad (cmake/test_data.cmake, tests/CMakeLists.txt).
set -euo pipefail
vqf_dir=$1 build=${2:-build} runs=${3:-9}
here=$(cd "$(dirname "$0")/../.." && pwd)
trial="$here/../shared/data/broad/01_undisturbed_slow_rotation_A.csv.gz"
[[ -d $here/../shared/data/broad ]] || trial="$here/tests/data/broad/05_undisturbed_slow_rotation_with_breaks_B.csv.gz"
echo "trial: $trial"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -std=c++17 -O2 -g -DNDEBUG -DHEADINGD_BENCH_BROAD_TRIAL="\"$trial\"" -I"$vqf_dir" \
  "$here/tests/bench/vqf/vqf_broad_bench.cpp" "$vqf_dir/vqf.cpp" -o "$work/vqf-bench" -lbenchmark -lpthread
per_sample() { sed -n 's/.*time_per_sample=\([0-9.]*\)\([nu]\)s.*/\1 \2/p' | awk '{ print $2 == "u" ? $1 * 1000 : $1 }'; }
for ((i = 0; i < runs; ++i)); do
  h=$("$build/tests/headingd-bench" --benchmark_filter=BroadTrial 2>/dev/null | per_sample)
  v=$("$work/vqf-bench" 2>/dev/null | per_sample)
  echo "run $((i + 1)): headingd $h ns, VQF $v ns"
done | tee "$work/runs"
awk '{ h[NR] = $4; v[NR] = $7; r[NR] = $4 / $7 }
  function median(a, n,   i, j, t) { for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
  END { printf "median per sample: headingd %.1f ns, VQF %.1f ns; median of the pairwise ratios headingd / VQF %.3f\n",
        median(h, NR), median(v, NR), median(r, NR) }' "$work/runs"
