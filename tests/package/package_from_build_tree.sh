#!/usr/bin/env bash
# CTest package.install: checks $HEADINGD_DEB when set, otherwise a package cpack makes from
# this build tree (pack_build_tree.sh); its tools' default paths then point into this
# checkout, which package_install_test.sh says and does not check.
#
#   package_from_build_tree.sh BUILD_DIR
set -euo pipefail
here=$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")
out=$("$here/pack_build_tree.sh" "$1" "$1/package")
echo "${out%$'\n'*}"
exec "$here/package_install_test.sh" "${out##*$'\n'}"
