#!/usr/bin/env bash
# Builds headingd (installing missing dependencies) and runs the whole test suite, then the
# unit and component tests again built with ASan+UBSan (sanitize.sh unit, in
# build-asan-unit/). Exits with ctest's exit code (or the build's, if the build fails), else
# the sanitizer run's.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$repo"

start=$(date +%s.%N)
report() {
  local rc=$? now
  now=$(date +%s.%N)
  echo "run-tests: exit code $rc, total time (build and tests) $(awk -v a="$start" -v b="$now" 'BEGIN { printf "%.1f", b - a }') s"
}
trap report EXIT

tools/scripts/build.sh
rc=0
ctest --test-dir build --output-on-failure -j2 || rc=$?
sanitizer_rc=0
tools/scripts/sanitize.sh unit --jobs 2 || sanitizer_rc=$?
((rc != 0)) || rc=$sanitizer_rc
exit $rc
