#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz: clang, ASan, UBSan) and runs each on its seed
# corpus and then for SECONDS of new inputs; prints per target the executions and coverage
# (libFuzzer's cov: edges and ft: features) and the total.
#
# Usage: fuzz.sh [--build-dir DIR] [--build-only | --no-build] [--jobs N] [SECONDS [TARGET...]]
#   SECONDS      fuzzing time per target (default 60); 0 runs the seeds only
#   TARGET       names as in tests/fuzz/corpus/ (default: all)
#   --build-dir  the clang tree (default build/fuzz); CTest passes <build>/fuzz
#   --build-only configure and build, run nothing (CTest's fuzz.build_tree)
#   --no-build   run what is built (CTest's fuzz.<target>)
#   --jobs N     build jobs (default nproc)
# ccache is used when the environment says so (CMAKE_CXX_COMPILER_LAUNCHER=ccache).
# Each run starts from the committed seeds: new inputs go to DIR/work/<target>, a crash's
# input to DIR/artifacts/<target>/ (add it to tests/fuzz/corpus/<target>/ once fixed: the
# seeds are the regression tests), libFuzzer's log to DIR/logs/<target>.log.
# Exit: 0 no target found anything, 1 a target crashed or a build failed, 77 no clang or
# libFuzzer (clang and libclang-rt-14-dev, tools/scripts/install-deps.sh).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build_dir=$repo/build/fuzz
mode=all
jobs=$(nproc)
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --build-dir) build_dir=$2; shift 2 ;;
    --build-only) mode=build; shift ;;
    --no-build) mode=run; shift ;;
    --jobs) jobs=$2; shift 2 ;;
    *) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
seconds=${1:-60}
shift || true
targets=("$@")
if ((${#targets[@]} == 0)); then
  for dir in "$repo"/tests/fuzz/corpus/*/; do targets+=("$(basename "$dir")"); done
fi

clang=$(command -v clang++ || true)
if [[ -z $clang || ! -e $("$clang" -print-file-name=libclang_rt.fuzzer-x86_64.a) ]]; then
  echo "fuzz.sh: needs clang++ with libFuzzer (apt-get install clang libclang-rt-14-dev)"
  exit 77
fi

if [[ $mode != run ]]; then
  start=$(date +%s)
  cmake -S "$repo" -B "$build_dir" -DHEADINGD_FUZZ=ON -DCMAKE_CXX_COMPILER="$clang" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$build_dir.configure.log" 2>&1 || {
    cat "$build_dir.configure.log"
    exit 1
  }
  cmake --build "$build_dir" -j"$jobs" --target headingd-fuzz-targets
  echo "fuzz.sh: built ${#targets[@]} targets in $build_dir in $(($(date +%s) - start)) s"
  [[ $mode == build ]] && exit 0
fi

mkdir -p "$build_dir/logs"
printf '%-18s %8s %12s %10s %7s %7s %7s  %s\n' target seconds executions exec/s cov ft seeds result
total=0
failed=0
for target in "${targets[@]}"; do
  binary=$build_dir/tests/fuzz/fuzz-$target
  seeds=$repo/tests/fuzz/corpus/$target
  [[ -x $binary ]] || { echo "fuzz.sh: $binary not built (run without --no-build)"; exit 1; }
  [[ -d $seeds ]] || { echo "fuzz.sh: no seed corpus $seeds"; exit 1; }
  work=$build_dir/work/$target
  artifacts=$build_dir/artifacts/$target
  log=$build_dir/logs/$target.log
  rm -rf "$work"
  mkdir -p "$work" "$artifacts"
  # Exit codes set explicitly: libFuzzer's default for a crash is 77, CTest's "skipped".
  run=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
    -error_exitcode=1 -timeout_exitcode=1 -artifact_prefix="$artifacts/")
  ((seconds == 0)) && run=(-runs=0 "${run[@]:1}")
  result=ok
  "$binary" "${run[@]}" "$work" "$seeds" >"$log" 2>&1 || result=FAILED
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  elapsed=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -n 1)
  [[ -n $elapsed ]] || elapsed=$seconds
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -n 1 || true)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  rate=$(awk -v e="${execs:-0}" -v s="$elapsed" 'BEGIN { printf "%d", (s > 0 ? e / s : e) }')
  printf '%-18s %8s %12s %10s %7s %7s %7s  %s\n' "$target" "$elapsed" "${execs:-?}" "$rate" "${cov:-?}" "${ft:-?}" \
    "$(find "$seeds" -type f | wc -l)" "$result"
  total=$((total + ${execs:-0}))
  if [[ $result != ok ]]; then
    failed=1
    grep -E 'invariant failed|runtime error|ERROR: AddressSanitizer|SUMMARY|Test unit written' "$log" | head -n 20 ||
      tail -n 40 "$log"
  fi
done
echo "fuzz.sh: $total executions in all"
exit $failed
