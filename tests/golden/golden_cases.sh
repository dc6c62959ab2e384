#!/usr/bin/env bash
# The golden replay cases: inputs from the repository alone, run through headingd-replay
# (and headingd-sim for the simulated walk). Sourced by compare_test.sh and by
# tools/scripts/regenerate-golden.sh, so the check and the regeneration run the same commands.
#
# golden_run_case NAME OUTDIR: writes OUTDIR/NAME.csv (the full replay output) and
# OUTDIR/NAME.counters.json (headingd-replay's counters, without its timing field).
# Needs $golden_repo, $golden_replay, $golden_sim, $golden_calibrate. A case may write more
# outputs (golden_extra_outputs NAME lists them): they are compared whole.
golden_cases=(broad05 sim_urban_walk broad32_calibrated recording_walk)

golden_run_case() {
  local name=$1 out=$2 err
  err=$(mktemp)
  case $name in
    broad05)  # BROAD trial 05 (the demo trial), default estimator parameters
      "$golden_replay" --imu-csv "$golden_repo/config/demo/05_undisturbed_slow_rotation_with_breaks_B.csv.gz" \
        --out "$out/$name.csv" 2>"$err" ;;
    sim_urban_walk)  # simulated 10-minute town walk with GPS, WMM and a 3° declination anomaly
      "$golden_sim" --scenario urban-walk --seed 1 --decl-anomaly-deg 3 --out-dir "$out/$name.sim" >/dev/null
      "$golden_replay" --imu-csv "$out/$name.sim/imu.csv" --nmea "$out/$name.sim/gps.nmea" \
        --wmm "$golden_repo/config/wmm/WMM2025.COF" --out "$out/$name.csv" 2>"$err"
      rm -rf "$out/$name.sim" ;;
    broad32_calibrated)  # BROAD trial 32 (magnet attached), calibrated on its magnet window
      # (ellipsoid fit), replayed with that calibration and the shipped config/estimator.toml
      # (run from the repository, so the file names the trial by the same relative path anywhere)
      (cd "$golden_repo" && "$golden_calibrate" --imu-csv tests/data/broad/32_disturbed_attached_magnet_1cm.csv.gz \
        --method ellipsoid --first-sample 11430 --end-sample 27140 --out "$out/$name.calibration.toml" 2>/dev/null)
      "$golden_replay" --imu-csv "$golden_repo/tests/data/broad/32_disturbed_attached_magnet_1cm.csv.gz" \
        --config "$golden_repo/config/estimator.toml" --calib "$out/$name.calibration.toml" \
        --out "$out/$name.csv" 2>"$err" ;;
    recording_walk)  # a black-box recording of a live run (vcan + pty in the VM; tests/data/recordings)
      mkdir -p "$out/$name.rec"
      tar -xzf "$golden_repo/tests/data/recordings/sim-walk-30s.tar.gz" -C "$out/$name.rec"
      "$golden_replay" --recording "$out/$name.rec/sim-walk-30s" --out "$out/$name.csv" 2>"$err"
      rm -rf "$out/$name.rec" ;;
    *) echo "golden: unknown case $name" >&2; return 2 ;;
  esac
  # The per-sample time is a timing figure, not an outcome.
  sed -E 's/,"estimator_ns_per_sample":[0-9.e+-]+//' "$err" >"$out/$name.counters.json"
  rm -f "$err"
}

golden_extra_outputs() {
  case $1 in
    broad32_calibrated) echo calibration.toml ;;
  esac
}

# golden_digest CSV: the committed form of a full output: its SHA-256 and row count, then
# the header, every 100th row and the last row (what a reviewer reads in a diff).
golden_digest() {
  local csv=$1
  echo "# sha256 $(sha256sum "$csv" | cut -d' ' -f1) rows $(($(wc -l <"$csv") - 1))"
  awk 'NR == 1 || (NR - 2) % 100 == 0 { print; last = NR } END { if (last != NR) print }' "$csv"
}
