#!/usr/bin/env bash
# Regenerates the bundled simulated capture in config/demo/ from the built tools, bit for bit:
#
#   headingd-sim --scenario urban-walk --seed 1            10 min walk: IMU CSV, NMEA, truth
#   headingd-candump-from-csv --can-config config/can-headingd.toml --start-time 1780315200
#                                                          the IMU as headingd's CAN frames
#
# and writes
#   sim-urban-walk-can.log.gz    candump -l log, 100 Hz, gyro/accel/mag frames with counters
#   sim-urban-walk.nmea          GGA, RMC, VTG at 1 Hz
#   sim-urban-walk-truth.csv.gz  the simulator's truth at 10 Hz (every 10th IMU row)
#
# The CAN log's timestamps are UNIX time and 1780315200 is 2026-06-01 12:00:00 UTC, the UTC the
# simulator gives IMU time 0 (tools/sim/README.md), so the daemon's log sources put the NMEA
# epochs and the frames on one clock. gzip -n stores no name or time, so the bytes depend on
# the tools alone.
#
# usage: tools/scripts/make-demo-capture.sh [--build DIR] [--out-dir DIR] [--check]
#   --build DIR    the build tree with headingd-sim and headingd-candump-from-csv built (build)
#   --out-dir DIR  where to write (config/demo)
#   --check        write into a temporary folder and compare with the files in --out-dir;
#                  exit 1 when they differ
set -euo pipefail
export LC_ALL=C
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=$repo/build
out_dir=$repo/config/demo
check=0
while (($#)); do
  case "$1" in
    --build) build=$(cd "$2" && pwd); shift 2 ;;
    --out-dir) out_dir=$2; shift 2 ;;
    --check) check=1; shift ;;
    *) echo "usage: make-demo-capture.sh [--build DIR] [--out-dir DIR] [--check]" >&2; exit 2 ;;
  esac
done
sim=$build/tools/sim/headingd-sim
candump_from_csv=$build/tools/candump_from_csv/headingd-candump-from-csv
for tool in "$sim" "$candump_from_csv"; do
  [[ -x "$tool" ]] || { echo "make-demo-capture: $tool is not built (cmake --build $build --target $(basename "$tool"))" >&2; exit 1; }
done

readonly scenario=urban-walk seed=1 start_time=1780315200 date=2026-06-01
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$sim" --scenario "$scenario" --seed "$seed" --date "$date" --cof "$repo/config/wmm/WMM2025.COF" \
  --out-dir "$work/sim" >/dev/null
"$candump_from_csv" --imu-csv "$work/sim/imu.csv" --can-config "$repo/config/can-headingd.toml" \
  --start-time "$start_time" --out "$work/can.log" >/dev/null

dest=$work/out
mkdir -p "$dest"
gzip -9n <"$work/can.log" >"$dest/sim-urban-walk-can.log.gz"
cp "$work/sim/gps.nmea" "$dest/sim-urban-walk.nmea"
# Truth: the header and every 10th row (10 Hz) of the columns a viewer of the demo needs.
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i }
  NR == 1 || (NR - 2) % 10 == 0 {
    print $col["t"] "," $col["heading_true_deg"] "," $col["heading_mag_deg"] "," $col["declination_deg"] "," \
          $col["disturbance_uT"] "," $col["indoor"] "," $col["activity"] "," $col["lat_deg"] "," $col["lon_deg"]
  }' "$work/sim/truth.csv" | gzip -9n >"$dest/sim-urban-walk-truth.csv.gz"

files=(sim-urban-walk-can.log.gz sim-urban-walk.nmea sim-urban-walk-truth.csv.gz)
if ((check)); then
  status=0
  for f in "${files[@]}"; do
    if cmp -s "$dest/$f" "$out_dir/$f"; then echo "same      $f"; else echo "DIFFERENT $f"; status=1; fi
  done
  exit "$status"
fi
mkdir -p "$out_dir"
for f in "${files[@]}"; do
  cp "$dest/$f" "$out_dir/$f"
  printf '%-30s %8d bytes\n' "$f" "$(stat -c %s "$out_dir/$f")"
done
