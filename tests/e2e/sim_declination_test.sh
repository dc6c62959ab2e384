#!/usr/bin/env bash
# Henriksson §6.3 in simulation with the default configuration: four straight 50 s walks in
# Stockholm, consumer-grade IMU and GPS. (1) a 3° local anomaly, no mounting yaw; (2) no
# anomaly, a 3° mounting yaw. The final estimates are the last row of the replay's output.
#
# One seed is one draw of the GPS course noise, which alone moves the result by about 0.4°:
# the mean course error of the simulated receiver over the walking epochs (σ_v 0.08 m/s,
# correlated over 2 s), read from gps_truth.csv, is RMS 0.38° over seeds 1-30 and beyond 0.5°
# on 6 of them (seeds 1, 2 and 8 here: +0.61, +0.72, +0.70). Add the consumer IMU's residual
# magnetometer rotation about z (RMS 0.27° over seeds 1-24) and accelerometer misalignment
# (mounting yaw, RMS 0.17°), which nothing in this walk can observe, and a 0.5° bound on
# every seed lies below the information in the data. So the test asserts the RMS error over
# seeds 1-8 as well as each seed. Thresholds are what this version achieves with some margin
# (measured when the test was written): declination RMS 0.59° / 0.66°, worst 1.13°; mounting
# yaw RMS 0.20°, worst 0.30° (within 0.5° on every seed).
#
# Usage: sim_declination_test.sh HEADINGD_SIM HEADINGD_REPLAY; environment SEEDS overrides 1-8.
set -euo pipefail
sim=$1 replay=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {  # run <name> <seed> <sim args...>; prints "declination sigma source mount" of the last row
  local name=$1 seed=$2; shift 2
  "$sim" --scenario thesis-declination --seed "$seed" --out-dir "$work/$name" "$@" >/dev/null
  "$replay" --imu-csv "$work/$name/imu.csv" --nmea "$work/$name/gps.nmea" --out "$work/$name/est.csv" 2>/dev/null
  head -1 "$work/$name/est.csv" | grep -q 'declination_source,mount_yaw_deg,heading_true_deg,mag_disturbed' \
    || { echo "missing GPS columns"; exit 1; }
  tail -1 "$work/$name/est.csv" | awk -F, '{print $10, $11, $12, $13}'
}
wmm_decl=7.6929  # WMM2025 at 59.33 N 18.07 E on 2026-06-01 (headingd-wmm)
failed=0
check_rms() {  # check_rms <what> <limit> <errors...>
  local what=$1 limit=$2; shift 2
  awk -v w="$what" -v l="$limit" 'BEGIN { for (i = 3; i < ARGC; ++i) s += ARGV[i] * ARGV[i];
    r = sqrt(s / (ARGC - 3)); printf "%s: RMS %.3f over %d seeds (limit %.2f)\n", w, r, ARGC - 3, l; exit !(r <= l) }' \
    x x "$@" || failed=1
}

anomaly_decl=() anomaly_mount=() mount_decl=() mount_mount=()
for seed in ${SEEDS:-1 2 3 4 5 6 7 8}; do  # SEEDS="$(seq 1 60)" for a study (then the limits are a guide)
  read -r decl sigma source mount < <(run "anomaly$seed" "$seed" --decl-anomaly-deg 3)
  [[ $source == *gps* ]] || { echo "seed $seed: declination source '$source' does not include GPS"; exit 1; }
  anomaly_decl+=("$(awk -v d="$decl" -v w=$wmm_decl 'BEGIN { print d - (w + 3) }')")
  anomaly_mount+=("$mount")
  read -r decl sigma source mount < <(run "mount$seed" "$seed" --mount-yaw-deg 3)
  [[ $source == *gps* ]] || { echo "seed $seed: declination source '$source' does not include GPS"; exit 1; }
  mount_decl+=("$(awk -v d="$decl" -v w=$wmm_decl 'BEGIN { print d - w }')")
  mount_mount+=("$(awk -v m="$mount" 'BEGIN { print m - 3 }')")
  echo "seed $seed: anomaly run decl error ${anomaly_decl[-1]}° mount ${anomaly_mount[-1]}°;" \
       "mount run decl error ${mount_decl[-1]}° mount error ${mount_mount[-1]}°"
done
# Every seed: declination within 1.2° (worst measured 1.13°), mounting yaw within 0.5° (0.30°).
for e in "${anomaly_decl[@]}" "${mount_decl[@]}"; do
  awk -v e="$e" 'BEGIN { exit !(e <= 1.2 && e >= -1.2) }' || { echo "declination error $e beyond 1.2°"; failed=1; }
done
for e in "${anomaly_mount[@]}" "${mount_mount[@]}"; do
  awk -v e="$e" 'BEGIN { exit !(e <= 0.5 && e >= -0.5) }' || { echo "mounting yaw error $e beyond 0.5°"; failed=1; }
done
check_rms "anomaly run: declination" 0.65 "${anomaly_decl[@]}"
check_rms "mount run: declination" 0.72 "${mount_decl[@]}"
check_rms "both runs: mounting yaw" 0.25 "${anomaly_mount[@]}" "${mount_mount[@]}"
exit $failed
