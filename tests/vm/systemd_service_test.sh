#!/usr/bin/env bash
# Host side of the CTest vm_systemd_service: boots the VM with systemd as PID 1
# (vm-run.sh --systemd) and runs systemd_service.sh there on the Debian package.
# The package: $HEADINGD_DEB when set, else what tools/scripts/build-deb.sh builds into
# OUTDIR (its last stdout line is the .deb's path); without either the test is skipped (77).
# usage: systemd_service_test.sh [OUTDIR]   (OUTDIR: where build-deb.sh writes; default a
#        temporary directory)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)

deb=${HEADINGD_DEB:-}
if [[ -z "$deb" ]]; then
  if [[ ! -x "$repo/tools/scripts/build-deb.sh" ]]; then
    echo "SKIP: no package: set HEADINGD_DEB=FILE.deb (tools/scripts/build-deb.sh is not there to build one)"
    exit 77
  fi
  outdir=${1:-$(mktemp -d)}
  mkdir -p "$outdir"
  echo "building the package: tools/scripts/build-deb.sh $outdir"
  deb=$("$repo/tools/scripts/build-deb.sh" "$outdir" | tail -n 1)
fi
[[ -f "$deb" ]] || { echo "FAIL: no package at '$deb'"; exit 1; }
deb=$(cd "$(dirname "$deb")" && pwd -P)/$(basename "$deb")

# The guest has its own /tmp and /run: a package there is shared into it.
rw=()
case "$deb" in /tmp/?*|/run/?*) rw=(--rw "$(dirname "$deb")") ;; esac

echo "package: $deb"
# Two CPUs: the daemon keeps one to itself under emulation (HEADING at 100 Hz); one CPU
# measured 40 Hz here, two 75 Hz on a loaded host (tools/scripts/vm/README.md).
exec "$repo/tools/scripts/vm-run.sh" --systemd --cpus 2 --timeout "${HEADINGD_VM_SYSTEMD_TIMEOUT:-400}" "${rw[@]}" -- \
  "$here/systemd_service.sh" "$deb"
