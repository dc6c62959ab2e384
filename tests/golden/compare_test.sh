#!/usr/bin/env bash
# Golden replay outputs (tests/golden/README.md): replays the cases of golden_cases.sh
# afresh and compares them with the committed digests, exactly: the SHA-256 of the whole
# output, the sampled rows and the counters. Any moved number fails, and the diff of the
# sampled rows shows where; regenerate on purpose with tools/scripts/regenerate-golden.sh.
# Usage: compare_test.sh REPO HEADINGD_REPLAY HEADINGD_SIM HEADINGD_CALIBRATE
set -euo pipefail
golden_repo=$1 golden_replay=$2 golden_sim=$3 golden_calibrate=$4
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source "$here/golden_cases.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

failed=0
for name in "${golden_cases[@]}"; do
  golden_run_case "$name" "$work"
  golden_digest "$work/$name.csv" >"$work/$name.digest.csv"
  for kind in digest.csv counters.json $(golden_extra_outputs "$name"); do
    if cmp -s "$here/$name.$kind" "$work/$name.$kind"; then
      echo "golden $name.$kind: identical"
    else
      echo "golden $name.$kind: DIFFERS from tests/golden/$name.$kind (first differences below)"
      diff "$here/$name.$kind" "$work/$name.$kind" | head -20 || true
      failed=1
    fi
  done
  echo "golden $name: $(($(wc -l <"$work/$name.csv") - 1)) rows compared by SHA-256"
done
[[ $failed == 0 ]] || { echo "FAIL: outputs moved; if on purpose, run tools/scripts/regenerate-golden.sh and commit"; exit 1; }
echo "PASS: every golden output is bit-identical"
