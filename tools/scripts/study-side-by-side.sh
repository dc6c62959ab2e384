#!/usr/bin/env bash
# headingd beside VQF and x-io Fusion on everything there is to run them on: every
# simulator scenario that has a motion to score, at each IMU grade and rate; the shared BROAD
# trials; the shared phone recordings, group by group. One markdown table per set, each
# filter scored the same way by headingd-study (plain total RMSE, then total / heading /
# inclination after one constant earth and body rotation are fitted per filter). A study, not
# a test: it prints numbers and judges nothing.
#
# Usage: study-side-by-side.sh [--build DIR] [--seeds N] [--rates "100 50"] [--grades "mems consumer phone"]
#                              [--only sim|broad|phones] [--scenarios "phone-texting ..."] [--set 'key = value' ...]
# The comparators are ../shared/anchors (VQF and Fusion as their authors publish them), built
# by their own build.sh into DIR/anchors; without ../shared/anchors only headingd is run, and
# the output says so.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
build="$here/build" seeds=5 rates="100 50" grades="mems consumer phone" only="" sets=()
scenarios="urban-walk run crawl thesis-declination shake shake-any handheld slow-rotation indoor-static moving-disturbances vehicle-ride
           phone-texting phone-calling phone-swinging phone-pocket phone-running phone-running-circles"
while [[ $# -gt 0 ]]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --rates) rates=$2; shift 2 ;;
    --grades) grades=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --scenarios) scenarios=$2; shift 2 ;;
    --set) sets+=(--set "$2"); shift 2 ;;
    *) sed -n '2,15p' "$0" >&2; exit 2 ;;
  esac
done
study="$build/tools/study/headingd-study"
[[ -x "$study" ]] || { echo "study-side-by-side: $study is not built (tools/scripts/build.sh)" >&2; exit 1; }
shared="$here/../shared"
anchor_args=()
if [[ -x "$shared/anchors/build.sh" ]]; then
  "$shared/anchors/build.sh" "$build/anchors" >/dev/null
  anchor_args=(--anchors "$build/anchors/bin")
  echo "comparators: VQF and Fusion from $shared/anchors (default parameters), on the same samples"
else
  echo "comparators: none (no ../shared/anchors): headingd alone"
fi

# One markdown row per run from the study's side-by-side block (headingd, then each anchor).
table() {  # table TITLE -- study arguments
  local title=$1; shift
  echo; echo "### $title"; echo
  "$study" "$@" "${anchor_args[@]}" "${sets[@]}" | awk -v anchors="${#anchor_args[@]}" '
    /^side by side/ { side = 1; next }
    side && /^$/ { side = 0; next }  # the table after it (openings) is not part of this one
    side && /^run / { n = split($0, h, "|"); printf "| run | Hz |"; for (i = 2; i <= n; ++i) { gsub(/ /, "", h[i]); printf " %s plain | %s fitted tot / head / incl |", h[i], h[i] } print ""
                      printf "|---|---:|"; for (i = 2; i <= n; ++i) printf "---:|---:|"; print ""; next }
    side { n = split($0, f, "|"); na = split(f[1], a, " ")
           name = a[1]; for (j = 2; j < na; ++j) name = name " " a[j]  # e.g. "phone-pocket seed 3"
           if (a[1] == "SIDE-MEAN") name = "**mean**"
           hz = (a[na] == "0.0") ? "native" : a[na]
           printf "| %s | %s |", name, hz
           for (i = 2; i <= n; ++i) { gsub(/\/ +/, "/", f[i]); split(f[i], v, " "); printf " %s | %s |", v[1], v[2] } print "" }
    !side && /^MEAN/ && anchors == 0 { print "| mean | " $2 " | " $3 " |" }'
}

if [[ -z $only || $only == sim ]]; then
  for scenario in $scenarios; do
    for grade in $grades; do
      for rate in $rates; do
        table "sim $scenario, $grade, $rate Hz, seeds 1-$seeds" sim --scenario "$scenario" --grade "$grade" \
          --seeds "1-$seeds" --rate "$rate"
      done
    done
  done
fi
if [[ -z $only || $only == broad ]] && [[ -d $shared/data/broad ]]; then
  table "BROAD, ../shared/data/broad (285.7 Hz)" broad --dir "$shared/data/broad"
fi
if [[ -z $only || $only == phones ]] && [[ -d $shared/data/phones ]]; then
  for group in nexus5 nexus5_magnets iphone iphone_magnets; do
    table "phones, $group (100 Hz)" broad --dir "$shared/data/phones/$group"
  done
fi
