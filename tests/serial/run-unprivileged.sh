#!/bin/sh
# Runs a command as an unprivileged user: as is when not root, else as nobody (uid/gid 65534,
# no supplementary groups, no capabilities) through util-linux's setpriv. For tests of what a
# process without CAP_SYS_ADMIN sees (a tty in exclusive mode refuses it with EBUSY).
set -eu
if [ "$(id -u)" -ne 0 ]; then
  exec "$@"
fi
exec setpriv --reuid=65534 --regid=65534 --clear-groups --inh-caps=-all --bounding-set=-all -- "$@"
