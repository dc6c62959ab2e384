#!/bin/sh
# Runs a command in a private network namespace (loopback up, multicast routed to it), so
# the LCM traffic of a test (udpm, ttl=0) can reach nothing but this test. Where namespaces
# are not permitted (not root, or a container without them) it runs the command directly:
# the tests then still use ttl=0 and a port of their own.
if unshare -n true 2>/dev/null; then
  exec unshare -n sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && exec "$@"' sh "$@"
fi
echo "in-private-net: no network namespace here, running in the host's" >&2
exec "$@"
