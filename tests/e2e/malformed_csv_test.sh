#!/usr/bin/env bash
# Malformed input fails with exit code 1 and a message naming the file, line and column;
# a bad config names the file, line and key.
set -euo pipefail
replay=$1 good_config=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

expect_failure() {  # expect_failure <pattern> <args...>
  local pattern=$1; shift
  if "$replay" "$@" 2>"$work/err"; then echo "accepted: $*"; exit 1; fi
  grep -q -- "$pattern" "$work/err" || { echo "message '$(cat "$work/err")' lacks '$pattern'"; exit 1; }
  echo "ok: $(cat "$work/err")"
}

printf 't,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n0,0,0,0,0,0,9.81,20,0,40\n0.01,0,0,0,0,abc,9.81,20,0,40\n' >"$work/bad_value.csv"
expect_failure "bad_value.csv:3: column 'acc_y'" --imu-csv "$work/bad_value.csv" --out "$work/o.csv"

printf 't,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n0,0,0,0,0,0,9.81,20,0,40\n0.01,0,0\n' >"$work/short.csv"
expect_failure "short.csv:3:" --imu-csv "$work/short.csv" --out "$work/o.csv"

printf 'time,gx\n0,0\n' >"$work/no_header.csv"
expect_failure "no column 't'" --imu-csv "$work/no_header.csv" --out "$work/o.csv"

expect_failure "cannot open" --imu-csv "$work/missing.csv" --out "$work/o.csv"

printf '[estimator]\ngyro_noise_rad_s = 0.05\nno_such_key = 1\n' >"$work/bad.toml"
printf 't,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n0,0,0,0,0,0,9.81,20,0,40\n' >"$work/ok.csv"
expect_failure "bad.toml:3.*no_such_key" --imu-csv "$work/ok.csv" --config "$work/bad.toml" --out "$work/o.csv"

# The shipped configuration is accepted.
"$replay" --imu-csv "$work/ok.csv" --config "$good_config" --out "$work/o.csv" 2>/dev/null

# A file without the magnetometer, or with one of its columns misspelt, is refused unless it
# is declared 6-axis (--no-mag): it used to be replayed without a heading reference, exit 0.
rm -f "$work/o.csv"
printf 't,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n0,0,0,0,0,0,9.81\n0.01,0,0,0,0,0,9.81\n' >"$work/six_axis.csv"
expect_failure "six_axis.csv:1: header lacks the magnetometer's columns 'mag_x', 'mag_y', 'mag_z'.*--no-mag" \
  --imu-csv "$work/six_axis.csv" --out "$work/o.csv"
printf 't,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_Z\n0,0,0,0,0,0,9.81,20,0,40\n' >"$work/mag_Z.csv"
expect_failure "mag_Z.csv:1: header lacks the magnetometer's column 'mag_z' (the header has 'mag_Z'" \
  --imu-csv "$work/mag_Z.csv" --out "$work/o.csv"
[ ! -e "$work/o.csv" ] || { echo "a refused replay left an output"; exit 1; }
"$replay" --imu-csv "$work/six_axis.csv" --no-mag --out "$work/o.csv" 2>/dev/null
[ "$(wc -l <"$work/o.csv")" -eq 3 ] || { echo "--no-mag: expected a header and 2 rows"; cat "$work/o.csv"; exit 1; }
echo "ok: --no-mag replays a 6-axis file"

# Other units than SI parse as well: the specific force in g (|a| = 1) is replayed, and named.
awk 'BEGIN { print "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z";
             for (i = 0; i < 1200; i++) printf "%.2f,0,0,0,0,0,1.0,20,0,40\n", i * 0.01 }' >"$work/in_g.csv"
"$replay" --imu-csv "$work/in_g.csv" --out "$work/o.csv" 2>"$work/err" || { cat "$work/err"; exit 1; }
grep -q "warning: IMU samples not in SI units? the accelerometer's mean norm over the first 10 s is 1.*(in g?)" \
  "$work/err" || { echo "no units warning: $(cat "$work/err")"; exit 1; }
echo "ok: $(grep -o 'warning: IMU samples not in SI units.*' "$work/err")"
