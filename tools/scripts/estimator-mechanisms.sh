#!/usr/bin/env bash
# Which mechanism of the estimator lets the tilt go, motion by motion: the same
# simulated motions and BROAD trials through the estimator of a baseline commit and of this
# checkout, each with one mechanism switched off or changed, scored by headingd-study.
#
# Usage: estimator-mechanisms.sh [--baseline COMMIT] [--build DIR] [--seeds N]
#   COMMIT  the estimator before the still-block gyro bias and the residual-based R_k
#           (default c9cad42). It is built in a temporary git
#           worktree with this checkout's simulator and study tool (tools/sim, tools/study),
#           so both estimators see the same motions.
#   DIR     this checkout's build folder with tools/study/headingd-study (default build)
#   N       seeds per simulated motion (default 12)
# Prints one markdown table per IMU grade (mems, consumer, and ideal with fewer rows): for
# each configuration, per motion the mean inclination RMSE, the worst inclination error
# during the motion and the worst from 5 s after it (deg), and BROAD's mean total /
# inclination RMSE at 285.7, 100 and 50 Hz.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
baseline=c9cad42 build="$here/build" seeds=12
while [[ $# -gt 0 ]]; do
  case $1 in
    --baseline) baseline=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    *) echo "usage: estimator-mechanisms.sh [--baseline COMMIT] [--build DIR] [--seeds N]" >&2; exit 2 ;;
  esac
done
current="$build/tools/study/headingd-study"
[[ -x "$current" ]] || { echo "estimator-mechanisms: $current is not built" >&2; exit 1; }

work=$(mktemp -d)
trap 'git -C "$here" worktree remove --force "$work/base" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
git -C "$here" worktree add -q "$work/base" "$baseline"
rm -rf "$work/base/tools/sim" "$work/base/tools/study"
cp -r "$here/tools/sim" "$here/tools/study" "$work/base/tools/"
grep -q 'add_subdirectory(study)' "$work/base/tools/CMakeLists.txt" || echo 'add_subdirectory(study)' >>"$work/base/tools/CMakeLists.txt"
# The study tool's trace names two outputs the baseline does not have; the tables do not use them.
sed -i 's/o\.gravity_noise_m_s2/0.0/; s/e\.counters()\.bias_still_blocks/e.counters().backtracks/' "$work/base/tools/study/main.cpp"
cp "$here"/tests/sim/*.cpp "$here"/tests/sim/*.hpp "$work/base/tests/sim/"
cmake -S "$work/base" -B "$work/base/build" -DHEADINGD_SHARED_DIR="$here/../shared" >/dev/null
cmake --build "$work/base/build" -j"$(nproc)" --target headingd-study >/dev/null
base="$work/base/build/tools/study/headingd-study"

row() {  # row LABEL TOOL GRADE [--set ...]
  local label=$1 tool=$2 grade=$3; shift 3
  local line="| $label |"
  for scenario in shake handheld slow-rotation; do
    line+=" $("$tool" sim --scenario "$scenario" --seeds "1-$seeds" --grade "$grade" "$@" |
      awk '/^MEAN/ { printf "%s / %s / %s", $5, $(NF-3), $(NF-2) }') |"
  done
  local broad=""
  for rate in 0 100 50; do
    local rate_arg=()
    [[ $rate != 0 ]] && rate_arg=(--rate "$rate")
    broad+="$("$tool" broad "${rate_arg[@]}" "$@" | awk '/^MEAN/ { printf "%s / %s", $4, $5 }'), "
  done
  echo "$line ${broad%, } |"
}

for grade in mems consumer ideal; do
  echo
  echo "### IMU grade: $grade; $seeds seeds per motion"
  echo
  echo "| configuration | shake: incl / worst / after 5 s | handheld | slow rotation | BROAD total / incl at 285.7, 100, 50 Hz |"
  echo "|---|---|---|---|---|"
  row "baseline $baseline" "$base" "$grade"
  if [[ $grade == ideal ]]; then  # perfect sensors: what is left is the estimator's own doing
    row "baseline, no rest bias (rest never detected)" "$base" "$grade" --set rest_min_duration_s=60
    row "this checkout" "$current" "$grade"
    continue
  fi
  row "baseline, R fixed at the standing level (back-tracking kept)" "$base" "$grade" \
    --set accel_noise_walking_m_s2=0.5 --set accel_noise_running_m_s2=0.5
  row "baseline, the level never steps up (no back-tracking, R fixed)" "$base" "$grade" \
    --set disturbance_up_to_walking=9000 --set disturbance_up_to_running=9999 \
    --set disturbance_down_to_standing=8000 --set disturbance_down_to_walking=9900
  row "baseline, no rest bias (rest never detected)" "$base" "$grade" --set rest_min_duration_s=60
  row "baseline, accelerometer pre-filter off" "$base" "$grade" --set accel_prefilter_time_constant_s=0
  row "baseline, pre-filter 3 s" "$base" "$grade" --set accel_prefilter_time_constant_s=3
  row "baseline, heading redefinition off" "$base" "$grade" --set redefine_heading_enter=-1 --set redefine_heading_leave=-0.9
  row "this checkout" "$current" "$grade"
  row "this checkout, R_k without the residual (κ = 0)" "$current" "$grade" --set accel_residual_gain=0
  row "this checkout, no bias from the gravity update in motion" "$current" "$grade" --set bias_motion_time_constant_s=0
  row "this checkout, samples taken as instantaneous (lag 0)" "$current" "$grade" --set vector_sample_lag_fraction=0
done
