#!/bin/sh
# Runs COMMAND with HEADINGD_SMALL_TMPFS naming a fresh tmpfs of SIZE (mount's size=, e.g.
# 256k) that a test may fill up, in private mount and network namespaces (the network one as
# in-private-net.sh: loopback with a multicast route, for LCM). Nothing is mounted on the
# host: the tmpfs goes with the namespace. Root gets `unshare -m -n`, others a user namespace
# too. Where namespaces are refused it exits 77 (CTest: skipped), saying why.
# usage: with-small-tmpfs.sh SIZE COMMAND [ARGS...]
size=$1
shift
dir=$(mktemp -d "${TMPDIR:-/tmp}/headingd-small-tmpfs.XXXXXX") || exit 1
trap 'rmdir "$dir"' EXIT
if [ "$(id -u)" -eq 0 ]; then ns="unshare -m -n"; else ns="unshare -r -m -n"; fi
if ! $ns sh -c "mount -t tmpfs -o size=$size tmpfs '$dir'" 2>/dev/null; then
  echo "with-small-tmpfs: cannot mount a tmpfs in a private mount namespace here ($ns): skipped" >&2
  exit 77
fi
$ns sh -c 'mount -t tmpfs -o size="$1" tmpfs "$2" && ip link set lo up && ip route add 224.0.0.0/4 dev lo &&
  HEADINGD_SMALL_TMPFS=$2 && export HEADINGD_SMALL_TMPFS && shift 2 && exec "$@"' sh "$size" "$dir" "$@"
status=$?
exit $status
