#!/usr/bin/env bash
# headingd-replay --place as a user runs it without a GPS capture: the simulated walk of
# Henriksson §6.3 (Stockholm, 2026-06-01, no local anomaly) replayed with the place and the
# date alone. The WMM there gives the declination (source "wmm", 7.69° as the simulator
# took it) and so true heading from the first sample: its RMS error against the truth after the
# first 10 s was 2.30° when this was written (limit 3°; without a place there is none). Bad places and dates exit with 2 and name the option.
set -euo pipefail
sim=$1 replay=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$sim" --scenario thesis-declination --seed 3 --out-dir "$work/walk" >/dev/null
"$replay" --imu-csv "$work/walk/imu.csv" --place 59.33,18.07 --place-date 2026-06-01 --out "$work/est.csv" \
  2>"$work/err"
grep -q "place 59.3300, 18.0700, 0 m on 2026.41: WMM-2025 declination 7.69 deg" "$work/err" \
  || { echo "no place line: $(cat "$work/err")"; exit 1; }
head -1 "$work/est.csv" | grep -q 'declination_deg,declination_sigma_deg,declination_source' \
  || { echo "missing the true-heading columns: $(head -1 "$work/est.csv")"; exit 1; }
# Every row: declination 7.69, source wmm. Columns: 10 declination, 12 source, 14 true heading.
awk -F, 'NR > 1 && ($10 < 7.68 || $10 > 7.70 || $12 != "wmm") { print "row " NR ": " $0; bad = 1; exit }
         END { exit bad }' "$work/est.csv"
# The true heading against the truth after the first 10 s (the estimator's start-up).
paste -d, <(cut -d, -f1,14 "$work/est.csv") <(cut -d, -f2 "$work/walk/truth.csv") |
  awk -F, 'NR > 1 && $1 >= 10 { d = $2 - $3; while (d > 180) d -= 360; while (d < -180) d += 360; s += d * d; n++ }
           END { r = sqrt(s / n); printf "true heading RMS error %.2f deg over %d samples\n", r, n; exit !(r < 3.0) }'

for bad in "--place 95,18" "--place 59,18,2000000" "--place 59" "--place 59,18 --place-date 2026-02-30" \
           "--place-date 2026-06-01"; do
  status=0
  # shellcheck disable=SC2086
  "$replay" --imu-csv "$work/walk/imu.csv" --out "$work/x.csv" $bad 2>"$work/err" || status=$?
  [ "$status" -eq 2 ] && grep -q -- "--place" "$work/err" || { echo "$bad: exit $status, $(cat "$work/err")"; exit 1; }
done
echo "ok"
