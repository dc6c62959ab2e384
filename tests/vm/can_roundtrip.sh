#!/usr/bin/env bash
# Runs where vcan0 exists (inside vm-run.sh): three frames sent with cansend on vcan0 must
# come back, exactly and in order, from candump on vcan0.
set -euo pipefail

expected=(
  "vcan0 123#DEADBEEF"                 # standard identifier, 4 data bytes
  "vcan0 18FEF100#0102030405060708"    # extended (J1939-style) identifier, 8 data bytes
  "vcan0 7FF#R"                        # remote frame, highest standard identifier
)

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# -L: log format "(time) iface id#data"; -n 3: exit after three frames; -T: give up after 10 s.
candump -L -n 3 -T 10000 vcan0 >"$work/dump" &
candump_pid=$!

# Send only once candump's socket is bound, or the first frame could be missed: the kernel
# lists every raw CAN receiver in /proc/net/can/rcvlist_all.
for _ in $(seq 100); do
  grep -qE '^ +vcan0 ' /proc/net/can/rcvlist_all 2>/dev/null && break
  sleep 0.05
done

for frame in "${expected[@]}"; do
  cansend vcan0 "${frame#vcan0 }"
done
wait "$candump_pid" || { echo "FAIL: candump exited with status $? (timeout?)"; cat "$work/dump"; exit 1; }

mapfile -t received < <(sed -E 's/^\([0-9.]+\) //' "$work/dump")
if [[ "${received[*]}" != "${expected[*]}" ]]; then
  echo "FAIL: frames differ"
  printf 'expected: %s\n' "${expected[@]}"
  printf 'received: %s\n' "${received[@]}"
  exit 1
fi
printf 'received: %s\n' "${received[@]}"
echo "PASS: ${#expected[@]} frames through vcan0 (cansend -> candump)"
