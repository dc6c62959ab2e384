#!/usr/bin/env bash
# Host side: runs COMMAND (vm-run.sh ...) and passes when its exit status is EXPECTED and,
# optionally, its stdout/stderr contain given lines.
# usage: expect_status.sh EXPECTED [--stdout LINE] [--stderr LINE] -- COMMAND [ARGS...]
set -uo pipefail
expected=$1
shift
want_out=()
want_err=()
while [[ "$1" != -- ]]; do
  case "$1" in
    --stdout) want_out+=("$2"); shift 2 ;;
    --stderr) want_err+=("$2"); shift 2 ;;
    *) echo "expect_status.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
shift

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$@" >"$work/out" 2>"$work/err"
status=$?
echo "--- stdout"; cat "$work/out"
echo "--- stderr"; cat "$work/err"
echo "---"

ok=1
if [[ "$status" != "$expected" ]]; then
  echo "FAIL: exit status $status, expected $expected"
  ok=0
fi
for line in "${want_out[@]}"; do
  grep -qxF -- "$line" "$work/out" || { echo "FAIL: stdout lacks the line '$line'"; ok=0; }
  grep -qxF -- "$line" "$work/err" && { echo "FAIL: '$line' is on stderr too"; ok=0; }
done
for line in "${want_err[@]}"; do
  grep -qxF -- "$line" "$work/err" || { echo "FAIL: stderr lacks the line '$line'"; ok=0; }
  grep -qxF -- "$line" "$work/out" && { echo "FAIL: '$line' is on stdout too"; ok=0; }
done
((ok)) && echo "PASS: exit status $status as expected"
((ok))
