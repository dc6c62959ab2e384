#!/usr/bin/env bash
# Builds the test suite with sanitizers (gcc) and runs it. docs/robustness.md, "Sanitizers
# and fuzzing", says what runs where.
#
# Usage: sanitize.sh [asan|unit|tsan|all] [--jobs N]      (default: all)
#   asan  AddressSanitizer + UndefinedBehaviorSanitizer, no recovery (the first report fails
#         the test), every target, in build-asan/; runs the whole suite except the tests that
#         cannot run there (below)
#   unit  the same sanitizers on the unit and component tests only (core, the file readers,
#         NMEA, serial on a pty, CAN decoding, WMM, GPS via gpsd's protocol, the recorder's
#         formats, the simulator, calibration), at -O1 with line tables only, in
#         build-asan-unit/: CI's run (.ci/run), about 13 min to build on 2 cores and 1.5 min
#         to run; not part of `all`, which runs `asan` over these and the rest
#   tsan  ThreadSanitizer in build-tsan/: the daemon's threaded parts, the rings, the recorder
#         and the daemon end to end on file sources (its estimator loop, source threads and
#         recorder writer), and its live sources on a pty
#   --jobs N  build jobs and ctest -j (default nproc)
# Prints the build and test times of each. Exit: 0 clean, else the first failing step's code.
#
# Left out of the ASan run, with the reason:
#   vm            boots a VM whose initramfs holds the host's binaries; sanitizer runtimes and
#                 their shadow memory are not part of it (and without KVM it takes minutes)
#   package       installs the build tree's binaries as a Debian package on this machine:
#                 instrumented binaries must not be installed
#   selfcontained builds its own clone with its own flags (docs/data.md, "Test data")
#   fuzz          the fuzz targets are their own clang ASan+UBSan tree (tools/scripts/fuzz.sh)
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
which=all
jobs=$(nproc)
while [[ $# -gt 0 ]]; do
  case $1 in
    asan | unit | tsan | all) which=$1; shift ;;
    --jobs) jobs=$2; shift 2 ;;
    *) echo "sanitize.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done

# Reports go to stderr and fail the process; the suppressions are for third-party code only.
export ASAN_OPTIONS=${ASAN_OPTIONS:-abort_on_error=0:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$repo/tools/scripts/sanitizers/lsan.supp}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:suppressions=$repo/tools/scripts/sanitizers/tsan.supp}

seconds_since() { echo $(($(date +%s) - $1)); }

# configure_and_build DIR BUILD_TYPE FLAGS TARGET...   (no target: all)
configure_and_build() {
  local dir=$1 build_type=$2 flags=$3
  shift 3
  local start
  start=$(date +%s)
  cmake -S "$repo" -B "$dir" -DHEADINGD_WERROR=ON -DCMAKE_BUILD_TYPE="$build_type" \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" >/dev/null
  # `|| return`: set -e does not act inside a function called from `run_x || rc=$?`.
  cmake --build "$dir" -j"$jobs" ${1:+--target "$@"} || { echo "sanitize: build of $dir failed" >&2; return 1; }
  echo "sanitize: build of $dir took $(seconds_since "$start") s"
}

# -fno-sanitize=vptr: gcc 12's vptr check breaks LCM's C++ subscription callback
# (lcm-cpp-impl.hpp, LCMMHSubscription::cb_func: with ASan+UBSan it reads its user_data as
# 0x1; with UBSan alone it reports an invalid vptr; plain, ASan alone or without the vptr
# check, a minimal subscriber receives its message). Every other UBSan check stays on.
asan_flags="-fsanitize=address,undefined -fno-sanitize=vptr -fno-sanitize-recover=all -fno-omit-frame-pointer"

run_asan() {
  local dir=$repo/build-asan start rc=0
  configure_and_build "$dir" RelWithDebInfo "$asan_flags" || return 1
  start=$(date +%s)
  ctest --test-dir "$dir" --output-on-failure -j"$jobs" -LE '^(vm|package|selfcontained|fuzz)$' || rc=$?
  echo "sanitize: ASan+UBSan suite took $(seconds_since "$start") s (exit $rc)"
  return $rc
}

# The unit and component tests: their executables and labels (tests/*/CMakeLists.txt).
unit_targets=(headingd-unit-tests headingd-nmea-tests headingd-can-tests headingd-serial-tests headingd-wmm-tests
  headingd-recording-tests headingd-gpsd-tests headingd-sim-tests headingd-calib-tests)
unit_labels='^(unit|nmea|serial|wmm|calib|gpsd|sim)$'

run_unit() {
  local dir=$repo/build-asan-unit start rc=0
  # -O1 -g1: what ASan is made for, with file and line in its reports, at less build time
  # than -O2 -g.
  configure_and_build "$dir" None "-O1 -g1 $asan_flags" \
    "${unit_targets[@]}" || return 1
  start=$(date +%s)
  # calib_ml's Monte Carlo is its own (slow) executable, left to the asan run.
  ctest --test-dir "$dir" --output-on-failure -j"$jobs" -L "$unit_labels" -E '^calib_ml\.' || rc=$?
  echo "sanitize: ASan+UBSan unit and component tests took $(seconds_since "$start") s (exit $rc)"
  return $rc
}

run_tsan() {
  local dir=$repo/build-tsan start rc=0
  # -Wno-error=tsan: gcc 12 warns that TSan does not model std::atomic_thread_fence, which
  # Boost.Asio's scheduler uses; a warning, not our code's, so it must not stop the build.
  configure_and_build "$dir" RelWithDebInfo "-fsanitize=thread -fno-omit-frame-pointer -Wno-error=tsan" \
    headingd-daemon-tests headingd-daemon-e2e-tests headingd-daemon-live-tests headingd headingd-replay || return 1
  start=$(date +%s)
  ctest --test-dir "$dir" --output-on-failure -j"$jobs" \
    -R '^(SampleRing|Recorder|RecorderStatus|DaemonEndToEnd|DaemonLiveSources)\.' || rc=$?
  echo "sanitize: TSan tests took $(seconds_since "$start") s (exit $rc)"
  return $rc
}

rc=0
if [[ $which == asan || $which == all ]]; then run_asan || rc=$?; fi
if [[ $which == unit ]]; then run_unit || rc=$?; fi
if [[ $which == tsan || $which == all ]]; then run_tsan || rc=$?; fi
exit $rc
