#!/usr/bin/env bash
# The tools' inputs and outputs as a careless user gives them (real files):
# - an output that is an input (also through a symbolic or hard link, also gzip) is refused
#   with exit 2 and the input is left as it was;
# - a replay that fails leaves no file under the output's name, and an earlier one as it was;
# - UNIX times come out of headingd-replay with all their digits, not as 1.7e+09;
# - headingd-eval with no row to score prints valid JSON (null and a reason), not nan;
# - a directory, a FIFO or /dev/zero as an input is refused at once with a message naming it;
# - a GPS value that cannot be used is counted in the replay's JSON;
# - a bad option exits 2 (not CLI11's 105/106).
set -euo pipefail
replay=$1 eval_tool=$2 nmea_dump=$3 wmm=$4 trial=$5
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

expect_status() {  # expect_status <status> <pattern> <command...>
  local want=$1 pattern=$2 status=0; shift 2
  timeout 20 "$@" >"$work/out" 2>"$work/err" || status=$?
  [[ $status == "$want" ]] || fail "exit $status, expected $want: $* ($(cat "$work/err"))"
  grep -q -- "$pattern" "$work/err" || fail "message '$(cat "$work/err")' lacks '$pattern'"
  echo "ok ($status): $(head -c 300 "$work/err")"
}

(zcat "$trial" || true) | head -301 >"$work/in.csv"  # zcat ends on SIGPIPE
[[ $(wc -l <"$work/in.csv") == 301 ]] || fail "cannot read $trial"
gzip -k "$work/in.csv"
ln -s "$work/in.csv" "$work/symlink.csv"
ln "$work/in.csv" "$work/hardlink.csv"
sum_before=$(sha256sum "$work/in.csv" "$work/in.csv.gz" | cut -d' ' -f1)

# 1. --out = --imu-csv destroyed the recording (exit 0).
expect_status 2 "is the same file as --imu-csv" "$replay" --imu-csv "$work/in.csv" --out "$work/in.csv"
expect_status 2 "is the same file as --imu-csv" "$replay" --imu-csv "$work/in.csv.gz" --out "$work/in.csv.gz"
expect_status 2 "is the same file as --imu-csv" "$replay" --imu-csv "$work/in.csv" --out "$work/symlink.csv"
expect_status 2 "is the same file as --imu-csv" "$replay" --imu-csv "$work/symlink.csv" --out "$work/hardlink.csv"
[[ $(sha256sum "$work/in.csv" "$work/in.csv.gz" | cut -d' ' -f1) == "$sum_before" ]] || fail "an input changed"

# 2. A failed replay leaves no half-written output, and an earlier output as it was.
{ cat "$work/in.csv"; echo "9,0,0,0,0,abc,9.81,20,0,40"; } >"$work/bad_last_row.csv"
expect_status 1 "bad_last_row.csv:302" "$replay" --imu-csv "$work/bad_last_row.csv" --out "$work/new.csv"
[[ ! -e $work/new.csv ]] || fail "a failed replay left new.csv"
echo "earlier" >"$work/earlier.csv"
expect_status 1 "bad_last_row.csv:302" "$replay" --imu-csv "$work/bad_last_row.csv" --out "$work/earlier.csv"
[[ $(cat "$work/earlier.csv") == earlier ]] || fail "a failed replay changed earlier.csv"
[[ $(find "$work" -name '.*' -type f | wc -l) == 0 ]] || fail "temporary files left: $(ls -a "$work")"

# 3. UNIX times keep their digits (they came out as 1.7e+09, every row alike).
awk -F, 'NR == 1 { print; next } { $1 = sprintf("%.6f", 1700000000 + $1); print }' OFS=, "$work/in.csv" >"$work/unix.csv"
"$replay" --imu-csv "$work/unix.csv" --out "$work/unix.out.csv" 2>/dev/null
sed -n 2p "$work/unix.out.csv" | grep -Eq '^1700000000\.[0-9]{9},' || fail "t printed as: $(sed -n 2p "$work/unix.out.csv")"
[[ $(cut -d, -f1 "$work/unix.out.csv" | sort -u | wc -l) == 301 ]] || fail "times collapsed"
paste -d, <(cut -d, -f1 "$work/unix.csv") <(cut -d, -f1 "$work/unix.out.csv") | tail -n +2 |
  awk -F, '{ if (($1 - $2) > 1e-6 || ($2 - $1) > 1e-6) { print "t " $1 " became " $2; exit 1 } }' || fail "times differ"
echo "ok: UNIX time row: $(sed -n 2p "$work/unix.out.csv" | cut -d, -f1-3)"

# 4. Nothing to score: valid JSON with null and a reason.
awk -F, 'NR == 1 { print "ref_w,ref_x,ref_y,ref_z,moving"; next } { print "1,0,0,0,0" }' "$work/in.csv" >"$work/still.csv"
"$replay" --imu-csv "$work/in.csv" --out "$work/est.csv" 2>/dev/null
"$eval_tool" --estimates "$work/est.csv" --reference "$work/still.csv" >"$work/eval.json"
python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d["total_rmse_deg"] is None and d["samples"] == 0 and d["reason"], d' \
  "$work/eval.json" || fail "eval printed: $(cat "$work/eval.json")"
echo "ok: $(cat "$work/eval.json")"

# 5. What is not a regular file is refused at once, naming it.
mkfifo "$work/fifo.nmea"
expect_status 1 "$work: is a directory" "$nmea_dump" "$work"
expect_status 1 "fifo.nmea: is a FIFO" "$nmea_dump" "$work/fifo.nmea"
expect_status 1 "/dev/zero: is a character device" "$wmm" --cof /dev/zero --lat 0 --lon 0 --alt-km 0 --date 2026-01-01
expect_status 1 "fifo.nmea: is a FIFO" "$replay" --imu-csv "$work/fifo.nmea" --out "$work/o.csv"
expect_status 1 "is a directory" "$eval_tool" --estimates "$work" --reference "$work/still.csv"

# 6. A GPS value that cannot be used (an RMC magnetic variation of 200 degrees) is left out and
#    counted in the replay's JSON: by the NMEA parser (nmea_invalid_fields); what passes the
#    parser but not the estimator's own checks is counted as gps_values_ignored, as on STATUS.
# write_rmc FILE TIME,DATE,VARIATION_EAST... : RMC sentences with valid checksums, one a field set.
write_rmc() {
  python3 - "$@" <<'PYTHON'
import functools, operator, sys
with open(sys.argv[1], "w") as out:
    for fields in sys.argv[2:]:
        time, date, variation = fields.split(",")
        body = f"GPRMC,{time},A,5230.000,N,01320.000,E,1.0,90.0,{date},{variation},{'E' if variation else ''},A"
        checksum = functools.reduce(operator.xor, body.encode(), 0)
        out.write(f"${body}*{checksum:02X}\r\n")
PYTHON
}
write_rmc "$work/bad_variation.nmea" 120000.00,010626,2.0 120001.00,010626,200.0 120002.00,010626,2.0
"$replay" --imu-csv "$work/in.csv" --nmea "$work/bad_variation.nmea" --out "$work/gps.csv" 2>"$work/err" ||
  fail "replay with NMEA failed: $(cat "$work/err")"
grep -q '"gps_epochs":3,.*"gps_values_ignored":0,.*"nmea_invalid_fields":1,' "$work/err" ||
  fail "the bad variation is not counted: $(cat "$work/err")"
echo "ok: $(grep -o '"gps_epochs[^n]*' "$work/err")"

# 6b. A date that parses but is not today (1024 weeks back, a receiver after a GPS week-number
#     rollover) is not the date the World Magnetic Model is evaluated on: counted, and the
#     epochs before it give the date in use.
write_rmc "$work/rollover.nmea" 120000.00,010626, 120000.20,010626, 120000.40,161006, 120000.60,161006,  # in the IMU's 1 s
"$replay" --imu-csv "$work/in.csv" --nmea "$work/rollover.nmea" --out "$work/gps.csv" 2>"$work/err" ||
  fail "replay with NMEA failed: $(cat "$work/err")"
grep -q '"gps_epochs":4,.*"gps_values_ignored":2,"gps_dates_not_believed":2,' "$work/err" ||
  fail "the rollover dates are not counted: $(cat "$work/err")"
echo "ok: $(grep -o '"gps_epochs[^n]*' "$work/err")"

# 6c. An output named - is standard output (it was a file named '-').
(cd "$work" && "$replay" --imu-csv in.csv --out - >stdout.csv 2>/dev/null) || fail "--out - failed"
[[ ! -e "$work/-" ]] || fail "--out - wrote a file named '-'"
[[ $(wc -l <"$work/stdout.csv") == 301 ]] || fail "--out - wrote $(wc -l <"$work/stdout.csv") lines to stdout"
echo "ok: --out - is standard output"

# 7. Bad options: 2, as every --help footer says.
for tool in "$replay" "$eval_tool" "$nmea_dump" "$wmm"; do
  expect_status 2 "" "$tool" --no-such-option
  # Captured first: grep -q stops reading at the match, and the tool writing the rest of its help
  # into a closed pipe would fail the pipeline (pipefail).
  help=$("$tool" --help)
  grep -q "Exit codes: 0" <<<"$help" || fail "$tool --help lists no exit codes"
done
expect_status 2 "required" "$eval_tool" --estimates "$work/est.csv"
echo "all passed"
