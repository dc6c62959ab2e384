#!/usr/bin/env bash
# True heading on simulated runs with GPS, the way the daemon sees them: headingd-sim writes
# the IMU CSV and the receiver's NMEA (with a 3° local declination anomaly), headingd-replay
# runs the whole pipeline (WMM reference field, declination from the GPS course), and the
# true-heading RMSE against the simulator's truth is printed per seed, with the mean, for
# each scenario × IMU grade × estimator variant. headingd-study scores the estimator without
# GPS; this is the study for what only a fix changes. A study, not a test: it judges nothing.
#
# Usage: study-true-heading.sh [--build DIR] [--seeds N] [--scenarios "urban-walk thesis-declination"]
#                              [--grades "consumer mems phone"] [VARIANT ...]
# A VARIANT is a list of [estimator] settings separated by ';', e.g.
#   'mag_rate_error_time_constant_s = 0'
# and "default" (the default when none is given) is the configuration as shipped.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build="$here/build" seeds=6 scenarios="urban-walk thesis-declination" grades="consumer mems phone" variants=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --scenarios) scenarios=$2; shift 2 ;;
    --grades) grades=$2; shift 2 ;;
    -*) sed -n '2,13p' "$0" >&2; exit 2 ;;
    *) variants+=("$1"); shift ;;
  esac
done
[[ ${#variants[@]} -gt 0 ]] || variants=(default)
sim="$build/tools/sim/headingd-sim" replay="$build/tools/headingd-replay"
for tool in "$sim" "$replay"; do
  [[ -x "$tool" ]] || { echo "study-true-heading: $tool is not built (tools/scripts/build.sh)" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# rmse EST TRUTH: the true-heading RMSE (deg) of headingd-replay's output against the
# simulator's truth, rows matched by order, columns by their header names.
rmse() {
  paste -d, "$1" "$2" | awk -F, '
    NR == 1 {
      for (i = 1; i <= NF; i++) if ($i == "heading_true_deg") { if (est) truth = i; else est = i }
      next
    }
    $est != "nan" { e = $est - $truth; e -= 360 * int(e / 360); if (e > 180) e -= 360; if (e <= -180) e += 360; s += e * e; n++ }
    END { printf "%.2f", sqrt(s / n) }'
}

echo "| scenario | grade | variant | seeds 1-$seeds: true-heading RMSE (deg) | mean |"
echo "|---|---|---|---|---:|"
for scenario in $scenarios; do
  for grade in $grades; do
    for seed in $(seq 1 "$seeds"); do
      "$sim" --scenario "$scenario" --seed "$seed" --imu-grade "$grade" --decl-anomaly-deg 3 \
        --out-dir "$work/$scenario-$grade-$seed" >/dev/null
    done
    for variant in "${variants[@]}"; do
      config=()
      if [[ $variant != default ]]; then
        { echo "[estimator]"; tr ';' '\n' <<<"$variant"; } >"$work/variant.toml"
        config=(--config "$work/variant.toml")
      fi
      row="" sum=0
      for seed in $(seq 1 "$seeds"); do
        run="$work/$scenario-$grade-$seed"
        "$replay" --imu-csv "$run/imu.csv" --nmea "$run/gps.nmea" --out "$work/est.csv" "${config[@]}" 2>/dev/null
        r=$(rmse "$work/est.csv" "$run/truth.csv")
        row+="$r " sum=$(awk -v a="$sum" -v b="$r" 'BEGIN { print a + b }')
      done
      echo "| $scenario | $grade | $variant | $row| $(awk -v s="$sum" -v n="$seeds" 'BEGIN { printf "%.2f", s / n }') |"
    done
  done
done
