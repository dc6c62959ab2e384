#!/usr/bin/env bash
# Host side of the CTest vm_systemd_service: boots the VM with systemd as PID 1
# (vm-run.sh --systemd) and runs systemd_service.sh there on the Debian package.
# The package: $HEADINGD_DEB when set, else one cpack makes from BUILD_DIR
# (tests/package/pack_build_tree.sh; tools/scripts/build-deb.sh builds the release one).
# usage: systemd_service_test.sh BUILD_DIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)

out=$("$repo/tests/package/pack_build_tree.sh" "$1" "$1/package-vm")
echo "${out%$'\n'*}"
deb=${out##*$'\n'}
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
