#!/usr/bin/env bash
# Builds the Debian package headingd_<version>_<arch>.deb into OUTDIR (default: build-deb/)
# and prints its path as the last line of stdout (for scripts: deb=$(build-deb.sh | tail -1)).
#
#   tools/scripts/build-deb.sh [OUTDIR]
#
# How: a Release build of its own (build-deb/tree: the tools' default data paths point to
# /usr/share/headingd there, not into this checkout, so it cannot share build/), compiled
# with Debian's hardening flags (dpkg-buildflags: -O2, -fstack-protector-strong,
# _FORTIFY_SOURCE, relro/now), then `cpack -G DEB`, which packs exactly the project's
# install rules, strips the programs and computes Depends with dpkg-shlibdeps. Why CPack and
# not a debian/ folder with dpkg-buildpackage: the CMake install rules are already the one
# description of what goes where, and cpack needs neither debhelper nor a source-package
# layout (dpkg-buildpackage writes its results into the parent folder of the checkout);
# what debhelper would add (maintainer scripts for systemd and sysusers, compressed man
# pages and changelog) is in packaging/. packaging/README.md has the details; lintian
# reports no errors (tests/package/).
#
# Incremental: a second run rebuilds only what changed. Environment: JOBS (default nproc).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=$(mkdir -p "${1:-$repo/build-deb}" && cd "${1:-$repo/build-deb}" && pwd)
tree="$out/tree"
jobs=${JOBS:-$(nproc)}

# Reproducible dates (man pages, changelog) from the last commit.
SOURCE_DATE_EPOCH=$(git -C "$repo" log -1 --format=%ct 2>/dev/null || date +%s)
export SOURCE_DATE_EPOCH
export DEB_BUILD_MAINT_OPTIONS="hardening=+all"
cppflags=$(dpkg-buildflags --get CPPFLAGS)
cxxflags=$(dpkg-buildflags --get CXXFLAGS)
ldflags=$(dpkg-buildflags --get LDFLAGS)

{
  # Release with -O2 (dpkg-buildflags) instead of CMake's -O3; NDEBUG as in any Release.
  cmake -S "$repo" -B "$tree" \
    -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS="$cppflags $cxxflags" \
    -DCMAKE_CXX_FLAGS_RELEASE="-DNDEBUG" \
    -DCMAKE_EXE_LINKER_FLAGS="$ldflags" \
    -DCMAKE_INSTALL_PREFIX=/usr \
    -DHEADINGD_DATA_DIR=/usr/share/headingd \
    -DHEADINGD_BUILD_TESTS=OFF
  cmake --build "$tree" -j"$jobs"
  (cd "$tree" && cpack -G DEB -B "$out")
} >&2
# lintian: no errors, or fail (warnings are shown).
deb=$(ls -t "$out"/headingd_*.deb | head -1)
lintian --fail-on error "$deb" >&2
echo "$deb"
