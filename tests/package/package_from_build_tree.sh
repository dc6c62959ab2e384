#!/usr/bin/env bash
# CTest package.install: checks $HEADINGD_DEB when set (e.g. the last line of
# tools/scripts/build-deb.sh), otherwise a package cpack makes from this build tree.
#
#   package_from_build_tree.sh BUILD_DIR
set -euo pipefail
build=$1
here=$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")
deb=${HEADINGD_DEB:-}
if [[ -z "$deb" ]]; then
  mkdir -p "$build/package"
  rm -f "$build"/package/headingd_*.deb
  cpack -G DEB --config "$build/CPackConfig.cmake" -B "$build/package" > "$build/package/cpack.log" 2>&1 ||
    { cat "$build/package/cpack.log"; echo "FAIL: cpack"; exit 1; }
  deb=$(ls "$build"/package/headingd_*.deb)
  echo "package of this build tree (HEADINGD_DEB unset): $deb"
fi
exec "$here/package_install_test.sh" "$deb"
