#!/usr/bin/env bash
# How close to the truth can any estimator get the declination in Henriksson's §6.3 experiment
# (four straight 50 s walks, consumer GPS)? For each seed of headingd-sim's thesis-declination
# scenario (3° local anomaly, no mounting yaw) this prints four declination errors [deg]:
#
#   gps_oracle  the error an estimator would make if it knew the true heading of every epoch:
#               the mean of (reported course - true course) over the walking epochs
#               (speed >= 1 m/s), per walk, then over the four walks (Henriksson eqs. 5.1-5.2).
#               Only the receiver's course noise is in it; no IMU, no prior.
#   ideal_imu   headingd-replay's final declination with a perfect IMU (--imu-grade ideal).
#   consumer    headingd-replay's final declination with the consumer IMU (the default).
#   calibrated  the same consumer IMU replayed with --calib: headingd-calibrate --method
#               ellipsoid on a 60 s hand-held rotation of the same sensor (the simulator draws
#               a seed's sensor errors the same in every scenario: calib-rotation-long).
#
# and, over all seeds, the RMS of each column and how many seeds are beyond 0.5°.
#
# Usage: declination-information-floor.sh HEADINGD_SIM HEADINGD_REPLAY [SEEDS...]   (default 1-20)
# Environment SIM_ARGS replaces the simulator's run options "--decl-anomaly-deg 3", e.g.
#   SIM_ARGS="--lat -33.87 --lon 151.21 --date 2027-03-01 --mount-yaw-deg 3"
# (--lat, --lon and --date there also go to the calibration); HEADINGD_CALIBRATE is the
# calibration tool (default: calibrate/headingd-calibrate beside HEADINGD_REPLAY).
set -euo pipefail
sim=$1 replay=$2
shift 2
calibrate=${HEADINGD_CALIBRATE:-$(dirname "$replay")/calibrate/headingd-calibrate}
place_option() {  # place_option NAME DEFAULT: the value of --NAME in SIM_ARGS (the simulator's default otherwise)
  local value=$2 args i
  read -ra args <<<"${SIM_ARGS:-}"
  for ((i = 0; i + 1 < ${#args[@]}; ++i)); do [[ ${args[i]} == "--$1" ]] && value=${args[i + 1]}; done
  echo "$value"
}
place=(--lat "$(place_option lat 59.33)" --lon "$(place_option lon 18.07)" --date "$(place_option date 2026-06-01)")
seeds=("$@")
[[ ${#seeds[@]} -gt 0 ]] || mapfile -t seeds < <(seq 1 20)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

true_declination() {  # the run's true declination (WMM + anomaly), from sensor_errors.toml
  awk -F' = ' '$1 == "declination_deg" { print $2 }' "$1/sensor_errors.toml"
}

final_declination_error() {  # final_declination_error <run dir> [replay options...]
  local dir=$1
  shift
  "$replay" --imu-csv "$dir/imu.csv" --nmea "$dir/gps.nmea" --out "$dir/est.csv" "$@" 2>/dev/null
  tail -1 "$dir/est.csv" | awk -F, -v truth="$(true_declination "$dir")" '{ printf "%.3f", $10 - truth }'
}

gps_oracle_error() {  # gps_oracle_error <run dir>: course error averaged per walk, then over walks
  awk -F, 'NR > 1 && $3 == 1 && $7 >= 1.0 && $8 != "" {
      e = $8 - $12; e -= 360 * int(e / 360); if (e > 180) e -= 360; if (e < -180) e += 360
      walk = int(($12 + 45) / 90) % 4          # N, E, S, W
      sum[walk] += e; n[walk]++ }
    END { for (w in sum) { total += sum[w] / n[w]; ++walks } printf "%.3f", total / walks }' "$1/gps_truth.csv"
}

printf "%5s %11s %10s %9s %11s\n" seed gps_oracle ideal_imu consumer calibrated
rows=()
for seed in "${seeds[@]}"; do
  for grade in ideal consumer; do
    # shellcheck disable=SC2086 # SIM_ARGS is a list of options
    "$sim" --scenario thesis-declination --seed "$seed" ${SIM_ARGS:---decl-anomaly-deg 3} --imu-grade "$grade" \
      --out-dir "$work/$grade" >/dev/null
  done
  "$sim" --scenario calib-rotation-long --seed "$seed" "${place[@]}" --out-dir "$work/calibration" >/dev/null
  "$calibrate" --imu-csv "$work/calibration/imu.csv" --method ellipsoid "${place[@]}" \
    --out "$work/calibration.toml" >/dev/null 2>&1
  row="$(gps_oracle_error "$work/consumer") $(final_declination_error "$work/ideal")"
  row+=" $(final_declination_error "$work/consumer")"
  row+=" $(final_declination_error "$work/consumer" --calib "$work/calibration.toml")"
  rows+=("$row")
  # shellcheck disable=SC2086 # the row's four numbers
  printf "%5s %11s %10s %9s %11s\n" "$seed" $row
done
printf '%s\n' "${rows[@]}" | awk '{ for (c = 1; c <= 4; ++c) { s[c] += $c * $c; if ($c > 0.5 || $c < -0.5) far[c]++ } }
  END { printf "  RMS %11.3f %10.3f %9.3f %11.3f\n", sqrt(s[1] / NR), sqrt(s[2] / NR), sqrt(s[3] / NR), sqrt(s[4] / NR)
        printf "> 0.5 %7d/%-3d %6d/%-3d %5d/%-3d %7d/%-3d\n", far[1], NR, far[2], NR, far[3], NR, far[4], NR }'
