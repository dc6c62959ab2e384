#!/usr/bin/env bash
# Builds headingd (installing missing dependencies), replays the bundled BROAD recording
# through the estimator into out/demo/estimates.csv, scores it against the recording's
# optical reference and prints a short summary. Needs only bash, coreutils and awk.
set -euo pipefail
export LC_ALL=C
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$repo"

trial=05_undisturbed_slow_rotation_with_breaks_B
recording=config/demo/$trial.csv.gz
config=config/estimator.toml
out_dir=out/demo
estimates=$out_dir/estimates.csv
# VQF 9D's total, heading and inclination RMSE (deg) on this trial, as listed in
# ../shared/data/broad/ANCHORS.md; read from there when that file is present.
vqf="0.99 0.92 0.35"
anchors=${HEADINGD_SHARED_DIR:-$repo/../shared}/data/broad/ANCHORS.md

tools/scripts/build.sh
mkdir -p "$out_dir"

# The replay prints its counters as one JSON line on stderr.
counters=$(build/tools/headingd-replay --imu-csv "$recording" --config "$config" --out "$estimates" 2>&1 >/dev/null) || {
  echo "run-demo: headingd-replay failed: $counters" >&2
  exit 1
}
counters=$(printf '%s\n' "$counters" | tail -n 1)
scores=$(build/tools/headingd-eval --estimates "$estimates" --reference "$recording")

# Value of a numeric key in a flat one-line JSON object.
json() {
  printf '%s\n' "$1" | awk -v key="\"$2\":" '{
    i = index($0, key); if (i == 0) { print "?"; exit }
    v = substr($0, i + length(key)); sub(/[,}].*/, "", v); print v }'
}

# The trial's row in ANCHORS.md: | trial | tot / head / incl (VQF) | ...
if [[ -r "$anchors" ]]; then
  cell=$(awk -F'|' -v t="$trial" '$2 ~ "^ *" t " *$" { print $3; exit }' "$anchors" | tr -d ' ')
  [[ "$cell" =~ ^[0-9.]+/[0-9.]+/[0-9.]+$ ]] && vqf=${cell//\// }
fi
read -r vqf_total vqf_heading vqf_inclination <<<"$vqf"

for key in rows accepted gaps clock_jumps non_finite duplicate_time backwards_time non_finite_mag; do
  value=$(json "$counters" "$key")
  [[ "$value" =~ ^[0-9]+$ ]] || { echo "run-demo: no '$key' in the counters: $counters" >&2; exit 1; }
  printf -v "c_$key" '%s' "$value"
done
rejected=$((c_non_finite + c_duplicate_time + c_backwards_time))
restarts=$((c_rows - c_accepted - rejected))  # the first usable sample, gaps and clock jumps

# Duration from the time column, final attitude from the last row of the estimates.
IFS='|' read -r duration final_attitude < <(awk -F, '
  NR == 2 { t0 = $1 }
  NR > 1  { t1 = $1; last = $0 }
  END {
    split(last, f, ",")
    if (f[6] == "nan") att = "none (no usable sample yet)"
    else att = sprintf("roll %.2f, pitch %.2f, yaw %.2f deg", f[6], f[7], f[8])
    printf "%.2f|%s\n", t1 - t0, att }' "$estimates")

rmse_row() { printf '    %-12s %7.2f %8.2f %12.2f' "$1" "$2" "$3" "$4"; }

cat <<SUMMARY

headingd demo: BROAD trial $trial (CC-BY-4.0, see config/demo/ATTRIBUTION.md)
  duration        $duration s
  samples         $c_rows: $c_accepted accepted, $rejected rejected (non-finite $c_non_finite, duplicate time $c_duplicate_time, backwards time $c_backwards_time);
                  $restarts (re)started the time base ($c_gaps gaps, $c_clock_jumps clock jumps), $c_non_finite_mag without magnetometer
  final attitude  $final_attitude (sensor to NED, yaw from magnetic north)
  estimator       $(json "$counters" estimator_ns_per_sample) ns/sample
  RMSE against the optical reference, deg, over $(json "$scores" samples) scored samples ($(json "$scores" failed_samples) without an estimate):
                      total  heading  inclination
$(rmse_row headingd "$(json "$scores" total_rmse_deg)" "$(json "$scores" heading_rmse_deg)" "$(json "$scores" inclination_rmse_deg)")
$(rmse_row "VQF 9D" "$vqf_total" "$vqf_heading" "$vqf_inclination")   (ANCHORS.md)
  estimates in    $estimates
SUMMARY
