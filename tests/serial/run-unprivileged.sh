#!/bin/sh
# Runs a command without privileges: as is when not root, else as root with every capability
# dropped (util-linux's setpriv: empty bounding, inheritable and ambient sets). What a tty in
# exclusive mode checks is CAP_SYS_ADMIN, not the uid, so this takes the path an unprivileged
# headingd (the unit's user) takes: open() fails with EBUSY. The uid stays 0 on purpose: the
# checkout may sit where another user cannot read it (/root, a mktemp -d folder).
set -eu
if [ "$(id -u)" -ne 0 ]; then
  exec "$@"
fi
exec setpriv --inh-caps=-all --ambient-caps=-all --bounding-set=-all -- "$@"
