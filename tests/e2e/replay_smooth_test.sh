#!/usr/bin/env bash
# headingd-replay --smooth on one BROAD trial, as a user runs it: one row per input row with
# the documented header, the same bytes twice, the heading no worse than the causal filter's
# (fast combined motion: 2.02 deg causal, 1.97 smoothed when this was written) and the
# inclination well below it (1.43 deg causal, 0.81 smoothed); with --place the true heading from
# the place's declination; --nmea is refused as a bad argument.
set -euo pipefail
source "$(dirname "$0")/../support/broad_trial_test.sh" "$@"

"$replay" --imu-csv "$trial" --out "$work/causal.csv" 2>/dev/null
"$replay" --imu-csv "$trial" --out "$work/smooth.csv" --smooth 2>"$work/counters.json"
expect_replay_csv "$work/smooth.csv"
grep -q "\"rows\":$in_rows," "$work/counters.json" || { echo "counters: $(cat "$work/counters.json")"; exit 1; }

"$replay" --imu-csv "$trial" --out "$work/smooth2.csv" --smooth 2>/dev/null
cmp -s "$work/smooth.csv" "$work/smooth2.csv" || { echo "the smoother is not deterministic"; exit 1; }

figure() { sed -n "s/.*\"$1\":\([0-9.]*\).*/\1/p" <<<"$2"; }
causal=$("$eval" --estimates "$work/causal.csv" --reference "$trial")
smooth=$("$eval" --estimates "$work/smooth.csv" --reference "$trial")
echo "causal:   $causal"
echo "smoothed: $smooth"
awk -v c="$(figure heading_rmse_deg "$causal")" -v s="$(figure heading_rmse_deg "$smooth")" \
  'BEGIN { exit !(s > 0 && s < c + 0.01) }' || { echo "the smoothed heading is worse than the causal one"; exit 1; }
awk -v c="$(figure inclination_rmse_deg "$causal")" -v s="$(figure inclination_rmse_deg "$smooth")" \
  'BEGIN { exit !(s > 0 && s < 0.75 * c) }' || { echo "inclination not smoothed below 0.75 x the causal filter's"; exit 1; }

# With --place: the true heading is the smoothed magnetic heading turned by the place's WMM
# declination (the rows carried zeros there before).
"$replay" --imu-csv "$trial" --out "$work/place.csv" --smooth --place 52.5,13.3 2>/dev/null
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  $col["yaw_deg"] != "nan" {
    d = $col["heading_true_deg"] - ($col["heading_mag_deg"] + $col["declination_deg"] - $col["mount_yaw_deg"])
    d = d - 360 * int(d / 360); if (d > 180) d -= 360; if (d < -180) d += 360
    if ($col["declination_source"] != "wmm" || d > 1e-3 || d < -1e-3 || $col["heading_mag_deg"] != $col["yaw_deg"]) bad++
    rows++ }
  END { exit !(rows > 0 && bad == 0) }' "$work/place.csv" || { echo "--smooth --place: true heading not from the declination"; exit 1; }

status=0
"$replay" --imu-csv "$trial" --out "$work/x.csv" --smooth --nmea "$trial" 2>"$work/err" || status=$?
[ "$status" -eq 2 ] && grep -q -- "--nmea" "$work/err" || { echo "--smooth --nmea: exit $status, $(cat "$work/err")"; exit 1; }
echo "ok"
