#!/usr/bin/env bash
# Prints the path of the Debian package to test: $HEADINGD_DEB when set (e.g. the last line
# of tools/scripts/build-deb.sh), otherwise a package `cpack -G DEB` makes from BUILD_DIR
# into OUTDIR (about a minute, instead of build-deb.sh's Release rebuild). A build-tree
# package's tools default to data paths in this checkout; the daemon reads only the
# conffile's absolute /usr/share/headingd paths, so it behaves as the release package's.
#
#   pack_build_tree.sh BUILD_DIR OUTDIR     (the path is the last line on stdout)
set -euo pipefail
build=$1 outdir=$2
if [[ -n "${HEADINGD_DEB:-}" ]]; then
  echo "package: HEADINGD_DEB"
  echo "$HEADINGD_DEB"
  exit 0
fi
mkdir -p "$outdir"
rm -f "$outdir"/headingd_*.deb
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$outdir" >"$outdir/cpack.log" 2>&1 ||
  { cat "$outdir/cpack.log" >&2; echo "FAIL: cpack" >&2; exit 1; }
echo "package of the build tree $build (HEADINGD_DEB unset)"
ls "$outdir"/headingd_*.deb
