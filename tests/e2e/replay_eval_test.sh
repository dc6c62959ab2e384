#!/usr/bin/env bash
# headingd-replay then headingd-eval on one BROAD trial: one output row per input row, the
# documented header, and an RMSE below the trial's accuracy limit.
set -euo pipefail
source "$(dirname "$0")/../support/broad_trial_test.sh" "$@"

"$replay" --imu-csv "$trial" --out "$work/est.csv" 2>"$work/counters.json"
expect_replay_csv "$work/est.csv"
grep -q '"non_finite":0' "$work/counters.json" || { echo "counters: $(cat "$work/counters.json")"; exit 1; }

result=$("$eval" --estimates "$work/est.csv" --reference "$trial")
echo "$result"
total=$(sed -n 's/.*"total_rmse_deg":\([0-9.]*\).*/\1/p' <<<"$result")
samples=$(sed -n 's/.*"samples":\([0-9]*\).*/\1/p' <<<"$result")
[ "$samples" -gt 20000 ] || { echo "too few scored samples: $samples"; exit 1; }
awk -v t="$total" 'BEGIN { exit !(t > 0 && t < 1.1) }' || { echo "total RMSE $total not in (0, 1.1)"; exit 1; }

# The same run again gives the same bytes: the estimator is deterministic.
"$replay" --imu-csv "$trial" --out "$work/est2.csv" 2>/dev/null
cmp -s "$work/est.csv" "$work/est2.csv" || { echo "replay is not deterministic"; exit 1; }
