#!/usr/bin/env bash
# The repository is self-contained: a clone with nothing beside it (no ../shared)
# builds and passes every test that reads real data, on the repository's subsets in tests/data
# (cmake/test_data.cmake). CTest runs this as `selfcontained.clone_without_shared`.
#
# Usage: selfcontained-test.sh SOURCE_DIR [JOBS]
#   SOURCE_DIR  a git checkout of headingd. Its HEAD is cloned: uncommitted changes are NOT
#               tested (they are listed as a warning); commit them first.
#   JOBS        parallel build jobs (default: nproc)
# Steps: clone into an empty temporary folder; configure with warnings as errors (every data
# set must resolve to the clone's tests/data); check that no CMake file but the helper names
# HEADINGD_SHARED_DIR; build only the data-reading tests and tools; run them with ctest; run
# the benchmark's BROAD case once. Prints each test's "data:" line, and the time taken.
# Exit: 0 all passed, 1 a step failed, 77 SOURCE_DIR is not a git checkout (e.g. an unpacked
# source package: nothing to clone).
set -euo pipefail
src=$(cd "$1" && pwd)
jobs=${2:-$(nproc)}
start=$(date +%s)

if ! git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "$src is not a git checkout: nothing to clone"
  exit 77
fi
head=$(git -C "$src" rev-parse --short HEAD)
changes=$(git -C "$src" status --porcelain)
if [[ -n $changes ]]; then
  echo "warning: changes not committed in $src are not part of this test (it clones HEAD $head):"
  echo "$changes"
fi

work=$(mktemp -d -t headingd-selfcontained.XXXXXX)
trap 'rm -rf "$work"' EXIT
git clone -q "$src" "$work/repo"
repo=$work/repo
# Nothing beside the clone: HEADINGD_SHARED_DIR's default, ../shared, is not there.
[[ $(ls -A "$work") == repo ]] || { echo "$work holds more than the clone"; exit 1; }
echo "clone of $head in $repo"

cmake -S "$repo" -B "$repo/build" -DHEADINGD_WERROR=ON >"$work/configure.log" || {
  cat "$work/configure.log"
  exit 1
}
grep "Test data" "$work/configure.log"
if grep "Test data" "$work/configure.log" | grep -v "$repo/tests/data/.* (in-repo subset)"; then
  echo "a data set resolved outside the clone's tests/data"
  exit 1
fi

# Every data set goes through cmake/test_data.cmake; the top CMakeLists.txt only defines it.
stray=$(grep -rl --include=CMakeLists.txt --include='*.cmake' HEADINGD_SHARED_DIR "$repo" |
  grep -v -x -e "$repo/CMakeLists.txt" -e "$repo/cmake/test_data.cmake" || true)
if [[ -n $stray ]]; then
  echo "HEADINGD_SHARED_DIR used outside cmake/test_data.cmake (use headingd_data_set): $stray"
  exit 1
fi

# The targets of the tests that read data, and the tools the shell tests run. Left out for
# their build time (the daemon, the simulator): the generalisation test (BROAD through the
# same test_data.hpp as the accuracy test) and the daemon's live-source test (mt3339.log,
# which the serial tests read too), and headingd-study (its default is the folder the
# e2e tests get from the same CMake function).
targets=(headingd-nmea-tests headingd-serial-tests headingd-wmm-tests headingd-accuracy-tests
  headingd-replay headingd-eval headingd-calibrate headingd-bench)
build_start=$(date +%s)
cmake --build "$repo/build" -j"$jobs" --target "${targets[@]}" >"$work/build.log" 2>&1 || {
  tail -n 60 "$work/build.log"
  exit 1
}
echo "build of ${#targets[@]} targets: $(($(date +%s) - build_start)) s"

# Whole binaries by label, then the data-reading tests of binaries that mostly do not read data.
failed=0
ctest --test-dir "$repo/build" -V -L '^(nmea|serial|wmm|accuracy)$' >"$work/ctest-labels.log" 2>&1 || failed=1
ctest --test-dir "$repo/build" -V \
  -R '^(e2e\.replay_eval_broad|e2e\.broad_magnet_calibration)$' \
  >"$work/ctest-named.log" 2>&1 || failed=1
for log in "$work"/ctest-*.log; do
  grep -E '(tests passed|tests failed|^\s+[0-9]+ - )' "$log" || true
  if [[ $failed -ne 0 ]]; then grep -B2 -A30 -E 'Failed|FAILED' "$log" | tail -n 80 || true; fi
done
# The data lines the tests printed (ctest -V prefixes them with the test's number).
sed -n 's/^[0-9]*: \(data: .*\)/\1/p' "$work"/ctest-*.log | sort | uniq -c
if sed -n 's/^[0-9]*: \(data: .*\)/\1/p' "$work"/ctest-*.log | grep -v "in-repo subset"; then
  echo "a test read data outside the clone's subset"
  failed=1
fi
for set in broad gpsd-logs wmm; do
  grep -q "data: $repo/tests/data/$set (in-repo subset" "$work"/ctest-*.log || { echo "no test read $set"; failed=1; }
done

# The benchmark's BROAD case: trial 05 of the subset.
bench=$("$repo/build/tests/headingd-bench" --benchmark_filter=BroadTrial --benchmark_min_time=0.01 2>&1) || failed=1
echo "$bench" | grep BroadTrial
grep -q "05_undisturbed_slow_rotation_with_breaks_B" <<<"$bench" || { echo "bench: no BROAD trial"; failed=1; }

echo "selfcontained: $([[ $failed -eq 0 ]] && echo passed || echo FAILED), $(($(date +%s) - start)) s in all"
exit $failed
