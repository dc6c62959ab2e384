#!/usr/bin/env bash
# Builds headingd (installing missing dependencies) and runs the whole test suite.
# Exits with ctest's exit code (or the build's, if the build fails).
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
ctest --test-dir build --output-on-failure -j2
