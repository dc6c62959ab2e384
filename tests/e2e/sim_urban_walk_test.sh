#!/usr/bin/env bash
# urban-walk: ten minutes in town with a 3° local declination anomaly, two
# buildings (no GPS, disturbed field), street transients; consumer IMU and GPS. True-heading
# RMSE against the simulator's truth for three configurations of the same runs:
#   default      Henriksson ch. 4 disturbance handling, declination from WMM + GPS course
#   no_handling  the ch. 4 detectors' thresholds so wide that K never drops to 0
#   models_only  declination from the models (WMM, receiver) alone: no GPS course epochs
# Asserted (three seeds each): the handling lowers the RMSE; GPS refines the declination
# (closer to the truth than the models, which are 3° off) and lowers the outdoor RMSE
# (indoors the heading error is dominated by the buildings' fields, whose sign decides
# whether a better declination helps or hurts there); the mean RMSE stays within 10 % of
# what was measured on 2026-12-05, 6.21° (6.33° before the observer's integral term learned
# outdoors; 7.80° on 2026-11-26, 7.47° before the ψ_g restore was turned on and the gait
# mounting yaw stopped using the filter's tilt).
set -euo pipefail
sim=$1 replay=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/no_handling.toml" <<'TOML'
[estimator]
mag_max_norm_deviation_uT = 1000.0
mag_max_dip_deviation_rad = 3.0
mag_max_reference_norm_deviation_uT = 1000.0
mag_max_reference_dip_deviation_rad = 3.0
TOML
cat >"$work/models_only.toml" <<'TOML'
[estimator]
decl_min_speed_mps = 50.0
TOML

# score <dir>: "rmse_all rmse_outdoor rmse_indoor final_declination_error" (degrees). Columns
# are found by their header names (est.csv then truth.csv, pasted side by side).
score() {
  paste -d, "$1/est.csv" "$1/truth.csv" | awk -F, '
    function wrap(a) { while (a > 180) a -= 360; while (a <= -180) a += 360; return a }
    NR == 1 {
      for (i = 1; i <= NF; i++) if (!($i in col)) col[$i] = i  # the first of a repeated name: est.csv
      est = col["heading_true_deg"]; est_decl = col["declination_deg"]
      for (i = 1; i <= NF; i++) if ($i == "heading_true_deg" && i != est) truth = i
      for (i = 1; i <= NF; i++) if ($i == "declination_deg" && i != est_decl) truth_decl = i
      indoor = col["indoor"]
      next
    }
    $est != "nan" { e = wrap($est - $truth); s += e * e; n++; if ($indoor == 1) { si += e * e; ni++ } else { so += e * e; no++ } }
    { last_decl_err = $est_decl - $truth_decl }
    END { printf "%.3f %.3f %.3f %.3f\n", sqrt(s / n), sqrt(so / no), sqrt(si / ni), last_decl_err }'
}

failed=0
declare -A total outdoors
limit=6.8
for seed in 1 2 3; do
  "$sim" --scenario urban-walk --seed "$seed" --decl-anomaly-deg 3 --out-dir "$work/s$seed" >/dev/null
  for cfg in default no_handling models_only; do
    args=()
    [[ $cfg == default ]] || args=(--config "$work/$cfg.toml")
    "$replay" --imu-csv "$work/s$seed/imu.csv" --nmea "$work/s$seed/gps.nmea" --out "$work/s$seed/est.csv" "${args[@]}" 2>/dev/null
    read -r all outdoor indoor decl_err < <(score "$work/s$seed")
    echo "seed $seed $cfg: true-heading RMSE $all° (outdoors $outdoor°, indoors $indoor°), final declination error $decl_err°"
    total[$cfg]=$(awk -v a="${total[$cfg]:-0}" -v b="$all" 'BEGIN { print a + b / 3 }')
    outdoors[$cfg]=$(awk -v a="${outdoors[$cfg]:-0}" -v b="$outdoor" 'BEGIN { print a + b / 3 }')
    eval "decl_${cfg}_$seed=$decl_err"
  done
  # GPS-refined declination beats the models' (3° off) on every seed.
  awk -v g="$(eval echo \$decl_default_$seed)" -v m="$(eval echo \$decl_models_only_$seed)" \
    'BEGIN { if (g < 0) g = -g; if (m < 0) m = -m; exit !(g < m) }' \
    || { echo "seed $seed: GPS-refined declination is not better than the models'"; failed=1; }
done
echo "mean true-heading RMSE: default ${total[default]}°, no handling ${total[no_handling]}°, models only ${total[models_only]}°"
echo "mean outdoor RMSE: default ${outdoors[default]}°, no handling ${outdoors[no_handling]}°, models only ${outdoors[models_only]}°"
awk -v d="${total[default]}" -v n="${total[no_handling]}" 'BEGIN { exit !(d < n) }' \
  || { echo "disturbance handling does not lower the RMSE"; failed=1; }
awk -v d="${outdoors[default]}" -v m="${outdoors[models_only]}" 'BEGIN { exit !(d < m) }' \
  || { echo "GPS-refined declination does not lower the outdoor RMSE"; failed=1; }
awk -v d="${total[default]}" -v l="$limit" 'BEGIN { exit !(d <= l) }' \
  || { echo "default RMSE ${total[default]}° above the limit $limit°"; failed=1; }
exit $failed
