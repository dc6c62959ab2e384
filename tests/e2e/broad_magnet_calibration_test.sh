#!/usr/bin/env bash
# BROAD's attached-magnet trials: calibrate on the trial's own magnet
# window with headingd-calibrate, replay the whole trial with --calib, score with
# headingd-eval. The magnet is on for only part of the trial (README of data/broad), so the
# calibration must be set aside when it no longer fits (mag_calibration_fit.hpp) and the
# result must beat the uncalibrated replay where the calibration is good (trial 34).
# Printed for each trial; asserted: trial 34 better calibrated than not, and in each the
# calibration is set aside at least once. The full set has both trials; the repository's
# subset (tests/data/broad) has 32 only, so there the set-aside is what is checked.
set -euo pipefail
calibrate=$1 replay=$2 eval=$3 broad=$4 kind=$5
source "$(dirname "$0")/../support/test_data.sh"
announce_data_set "$broad" "$kind" .csv.gz trials
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
total() { sed -n 's/.*"total_rmse_deg":\([0-9.]*\).*/\1/p' <<<"$1"; }
failed=0 ran=0
# trial, first and end row of the magnet window (the field strength swings from ~45 s to ~96 s
# in 34, ~40 s to ~95 s in 32; rows at 285.714 Hz)
for spec in "34_disturbed_attached_magnet_3cm 13140 28000" "32_disturbed_attached_magnet_1cm 11430 27140"; do
  read -r name first end <<<"$spec"
  trial="$broad/$name.csv.gz"
  [[ -e $trial ]] || { echo "$name: not in this set"; continue; }
  ran=$((ran + 1))
  "$calibrate" --imu-csv "$trial" --method ellipsoid --first-sample "$first" --end-sample "$end" \
    --out "$work/$name.toml" 2>/dev/null
  "$replay" --imu-csv "$trial" --out "$work/raw.csv" 2>/dev/null
  "$replay" --imu-csv "$trial" --calib "$work/$name.toml" --out "$work/cal.csv" 2>"$work/counters.json"
  raw=$("$eval" --estimates "$work/raw.csv" --reference "$trial")
  cal=$("$eval" --estimates "$work/cal.csv" --reference "$trial")
  echo "$name uncalibrated $raw"
  echo "$name calibrated   $cal $(tail -n 1 "$work/counters.json")"
  grep -q '"mag_calibration_set_aside":[1-9]' "$work/counters.json" \
    || { echo "$name: the calibration was never set aside"; failed=1; }
  if [[ $name == 34_* ]]; then
    awk -v c="$(total "$cal")" -v r="$(total "$raw")" 'BEGIN { exit !(c < 0.75 * r) }' \
      || { echo "$name: calibrated $(total "$cal") not clearly below uncalibrated $(total "$raw")"; failed=1; }
  fi
done
# The full set has both trials, the subset one: anything less is missing data, not a pass.
want=1
[[ $kind == "full set" ]] && want=2
[[ $ran -ge $want ]] || { echo "$ran attached-magnet trials (32, 34) in $broad, $want expected"; failed=1; }
exit $failed
