#!/usr/bin/env bash
# Rewrites tests/golden/*.digest.csv and *.counters.json from the current build, for a change
# that moves the estimates on purpose: run it, read the diff, commit it with the reason.
# Usage: tools/scripts/regenerate-golden.sh [BUILD_DIR]   (default build/)
set -euo pipefail
golden_repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${1:-$golden_repo/build}
golden_replay=$build/tools/headingd-replay
golden_sim=$build/tools/sim/headingd-sim
golden_calibrate=$build/tools/calibrate/headingd-calibrate
source "$golden_repo/tests/golden/golden_cases.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for name in "${golden_cases[@]}"; do
  golden_run_case "$name" "$work"
  golden_digest "$work/$name.csv" >"$golden_repo/tests/golden/$name.digest.csv"
  for kind in counters.json $(golden_extra_outputs "$name"); do
    cp "$work/$name.$kind" "$golden_repo/tests/golden/$name.$kind"
  done
  echo "tests/golden/$name: $(($(wc -l <"$work/$name.csv") - 1)) rows"
done
git -C "$golden_repo" diff --stat -- tests/golden || true
