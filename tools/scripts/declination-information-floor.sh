#!/usr/bin/env bash
# How close to the truth can any estimator get the declination in Henriksson's §6.3 experiment
# (four straight 50 s walks, consumer GPS)? For each seed of headingd-sim's thesis-declination
# scenario (3° local anomaly, no mounting yaw) this prints three declination errors [deg]:
#
#   gps_oracle  the error an estimator would make if it knew the true heading of every epoch:
#               the mean of (reported course - true course) over the walking epochs
#               (speed >= 1 m/s), per walk, then over the four walks (Henriksson eqs. 5.1-5.2).
#               Only the receiver's course noise is in it; no IMU, no prior.
#   ideal_imu   headingd-replay's final declination with a perfect IMU (--imu-grade ideal).
#   consumer    headingd-replay's final declination with the consumer IMU (the default).
#
# and, over all seeds, the RMS of each column and how many seeds are beyond 0.5°.
#
# Usage: declination-information-floor.sh HEADINGD_SIM HEADINGD_REPLAY [SEEDS...]   (default 1-20)
# Environment SIM_ARGS replaces the simulator's run options "--decl-anomaly-deg 3", e.g.
#   SIM_ARGS="--lat -33.87 --lon 151.21 --date 2027-03-01 --mount-yaw-deg 3"
set -euo pipefail
sim=$1 replay=$2
shift 2
seeds=("$@")
[[ ${#seeds[@]} -gt 0 ]] || seeds=($(seq 1 20))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

true_declination() {  # the run's true declination (WMM + anomaly), from sensor_errors.toml
  awk -F' = ' '$1 == "declination_deg" { print $2 }' "$1/sensor_errors.toml"
}

final_declination_error() {  # final_declination_error <run dir>
  "$replay" --imu-csv "$1/imu.csv" --nmea "$1/gps.nmea" --out "$1/est.csv" 2>/dev/null
  tail -1 "$1/est.csv" | awk -F, -v truth="$(true_declination "$1")" '{ printf "%.3f", $10 - truth }'
}

gps_oracle_error() {  # gps_oracle_error <run dir>: course error averaged per walk, then over walks
  awk -F, 'NR > 1 && $3 == 1 && $7 >= 1.0 && $8 != "" {
      e = $8 - $12; e -= 360 * int(e / 360); if (e > 180) e -= 360; if (e < -180) e += 360
      walk = int(($12 + 45) / 90) % 4          # N, E, S, W
      sum[walk] += e; n[walk]++ }
    END { for (w in sum) { total += sum[w] / n[w]; ++walks } printf "%.3f", total / walks }' "$1/gps_truth.csv"
}

printf "%5s %11s %10s %9s\n" seed gps_oracle ideal_imu consumer
rows=()
for seed in "${seeds[@]}"; do
  for grade in ideal consumer; do
    # shellcheck disable=SC2086 # SIM_ARGS is a list of options
    "$sim" --scenario thesis-declination --seed "$seed" ${SIM_ARGS:---decl-anomaly-deg 3} --imu-grade "$grade" \
      --out-dir "$work/$grade" >/dev/null
  done
  row="$(gps_oracle_error "$work/consumer") $(final_declination_error "$work/ideal") $(final_declination_error "$work/consumer")"
  rows+=("$row")
  printf "%5s %11s %10s %9s\n" "$seed" $row
done
printf '%s\n' "${rows[@]}" | awk '{ for (c = 1; c <= 3; ++c) { s[c] += $c * $c; if ($c > 0.5 || $c < -0.5) far[c]++ } }
  END { printf "  RMS %11.3f %10.3f %9.3f\n", sqrt(s[1] / NR), sqrt(s[2] / NR), sqrt(s[3] / NR)
        printf "> 0.5 %7d/%-3d %6d/%-3d %5d/%-3d\n", far[1], NR, far[2], NR, far[3], NR }'
