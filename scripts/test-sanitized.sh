#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer with floating-point traps:
# a Debug build (assertions on) with SKYBAND_SANITIZE=ON in its own build folder, then ctest
# with SKYBAND_FP_TRAPS=1 (tests/fp_traps.cpp: FE_INVALID and FE_DIVBYZERO raise SIGFPE).
#
# Usage: scripts/test-sanitized.sh [ctest arguments]   e.g. scripts/test-sanitized.sh -R '^io\.'
# Environment:
#   SKYBAND_SANITIZE_BUILD_DIR  build folder (default build-asan)
#   SKYBAND_SANITIZE_JOBS       build and ctest parallelism (default 2: the machine is shared)
#   SKYBAND_FP_TRAPS            default 1 (FE_INVALID + FE_DIVBYZERO); invalid or divbyzero: one
#                               alone; 0: no floating-point traps (tests/fp_traps.cpp)
#   SKYBAND_SANITIZE_TESTS      a ctest -R regular expression: build and run only the suites it
#                               matches (default: all of them)
#   SKYBAND_SANITIZE_EXCLUDE    with it, a ctest -E regular expression of suites left out
#   CC, CXX                     compiler at the first configure (default the system's, GCC)
# Any sanitizer report, trap or leak fails the test that caused it; ASan prints the stack.
# -O1 (not -O0): ASan's recommendation, and several times faster on the CGAL-heavy tests.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${SKYBAND_SANITIZE_BUILD_DIR:-build-asan}
JOBS=${SKYBAND_SANITIZE_JOBS:-2}

scripts/install-deps.sh

t0=$(date +%s)
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  GEN=()
  command -v ninja >/dev/null && GEN=(-G Ninja)
  cmake -S . -B "$BUILD_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
    -DSKYBAND_SANITIZE=ON -DSKYBAND_BUILD_BENCH=OFF -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=TRUE
fi
CTEST_SELECT=()
if [ -n "${SKYBAND_SANITIZE_TESTS:-}" ]; then
  # Suite layer.name is the executable test_layer_name (tests/CMakeLists.txt).
  CTEST_SELECT=(-R "$SKYBAND_SANITIZE_TESTS")
  [ -z "${SKYBAND_SANITIZE_EXCLUDE:-}" ] || CTEST_SELECT+=(-E "$SKYBAND_SANITIZE_EXCLUDE")
  mapfile -t targets < <(cd "$BUILD_DIR" && ctest -N "${CTEST_SELECT[@]}" |
                         sed -nE 's/^ *Test +#[0-9]+: ([a-z_]+)\.([a-z0-9_]+)$/test_\1_\2/p')
  [ ${#targets[@]} -gt 0 ] || { echo "test-sanitized: no suite matches '$SKYBAND_SANITIZE_TESTS'" >&2; exit 2; }
  echo "test-sanitized: ${#targets[@]} suites: ${targets[*]}"
  cmake --build "$BUILD_DIR" -j "$JOBS" --target "${targets[@]}"
else
  cmake --build "$BUILD_DIR" -j "$JOBS"
fi
t1=$(date +%s)
echo "test-sanitized: build took $((t1 - t0)) s"

export SKYBAND_FP_TRAPS=${SKYBAND_FP_TRAPS:-1}
# Boost.Test must not catch SIGFPE/SIGSEGV itself: then ASan's handler reports them with a stack.
export BOOST_TEST_CATCH_SYSTEM_ERRORS=no
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:check_initialization_order=1:strict_string_checks=1:handle_sigfpe=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Third-party leaks on libcitygml's failure path (scripts/lsan-suppressions.txt).
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan-suppressions.txt}
status=0
(cd "$BUILD_DIR" && ctest --output-on-failure -j "$JOBS" --timeout 3600 "${CTEST_SELECT[@]}" "$@") || status=$?
echo "test-sanitized: tests took $(( $(date +%s) - t1 )) s (build folder $BUILD_DIR, SKYBAND_FP_TRAPS=$SKYBAND_FP_TRAPS)"
exit $status
