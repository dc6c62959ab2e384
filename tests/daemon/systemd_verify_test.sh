#!/bin/sh
# systemd-analyze verify on systemd/headingd.service, and systemd-sysusers on
# systemd/headingd.sysusers into a scratch root. verify insists that ExecStart's binary
# exists, so the unit is checked as a copy that points at the freshly built binary
# (the only line that differs). Usage: systemd_verify_test.sh SOURCE_DIR HEADINGD_BINARY
set -eu
src=$1
bin=$2
command -v systemd-analyze >/dev/null || { echo "SKIP: no systemd-analyze"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

sed "s#^ExecStart=/usr/bin/headingd #ExecStart=$bin #" "$src/systemd/headingd.service" >"$tmp/headingd.service"
grep -q "^ExecStart=$bin " "$tmp/headingd.service" || { echo "FAIL: no ExecStart=/usr/bin/headingd line"; exit 1; }
out=$(systemd-analyze verify "$tmp/headingd.service" 2>&1) || { echo "FAIL: systemd-analyze verify: $out"; exit 1; }
# verify exits 0 on some warnings; any output is a problem worth failing on.
[ -z "$out" ] || { echo "FAIL: systemd-analyze verify said: $out"; exit 1; }
echo "systemd-analyze verify: clean"

# The exposure figure, for the record (not a pass/fail criterion).
systemd-analyze security --offline=true "$tmp/headingd.service" 2>/dev/null | grep -i "overall exposure" || true

# sysusers: the user and its dialout membership are created.
mkdir -p "$tmp/root/etc"
printf 'root:x:0:0:root:/root:/bin/sh\n' >"$tmp/root/etc/passwd"
printf 'root:x:0:\ndialout:x:20:\n' >"$tmp/root/etc/group"
systemd-sysusers --root="$tmp/root" "$src/systemd/headingd.sysusers" >/dev/null 2>&1
grep -q '^headingd:x:[0-9]*:[0-9]*:.*:/usr/sbin/nologin$' "$tmp/root/etc/passwd" || { echo "FAIL: no headingd user"; exit 1; }
grep -q '^dialout:x:20:headingd$' "$tmp/root/etc/group" || { echo "FAIL: headingd not in dialout"; exit 1; }
echo "systemd-sysusers: user headingd in dialout"
