#!/usr/bin/env bash
# Installs missing dependencies, then configures and builds headingd into build/ with
# warnings as errors. The build type is CMake's default here (RelWithDebInfo).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$repo"

tools/scripts/install-deps.sh
cmake -S . -B build -DHEADINGD_WERROR=ON
cmake --build build -j"$(nproc)"
