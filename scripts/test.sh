#!/usr/bin/env bash
# The README's test command: install what is missing, check the sources' layout, build (warnings
# as errors), run every test, build the library example against the installed package, build the
# benchmarks without the suites, then the sanitizer checks.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache keys on paths relative to the repository: the build folders below (and clones at other
# paths) share each other's objects wherever their flags agree.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
# The sanitized and fuzzing builds carry debug info (-g), for which ccache also hashes the build
# folder's absolute path unless told not to: without this, a clone at another path misses every one
# of their objects. (Their debug info then names the folder that first compiled each object.)
export CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
scripts/install-deps.sh
# The sources' layout (.clang-format), before the build: a quick failure.
scripts/check-format.sh
# Warnings are errors in CI's build (GCC 12, Release, the project's warning flags).
scripts/build.sh -DSKYBAND_WARNINGS_AS_ERRORS=ON
BUILD_DIR=${SKYBAND_BUILD_DIR:-build}
(cd "$BUILD_DIR" && ctest --output-on-failure -j "$(nproc)" --timeout 900)
# The library as a user gets it: installed into a prefix, and examples/ configured on its own
# against the installed package (find_package(skyband)), built and run on a closed-form case
# (examples/CMakeLists.txt: the SVF under the middle of a square roof, 0.445873527).
PREFIX="$BUILD_DIR/install-check"
rm -rf "$PREFIX"
cmake --install "$BUILD_DIR" --prefix "$PREFIX" >/dev/null
EXAMPLES_DIR="$BUILD_DIR/examples-installed"
GEN=()
if [ ! -f "$EXAMPLES_DIR/CMakeCache.txt" ] && command -v ninja >/dev/null; then GEN=(-G Ninja); fi
cmake -S examples -B "$EXAMPLES_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$(cd "$PREFIX" && pwd)" >/dev/null
cmake --build "$EXAMPLES_DIR" -j "$(nproc)"
"$EXAMPLES_DIR/svf_at_points" tests/data/meshes/canopy.obj 0,0,0 | grep -q '^0.000,0.000,0.000,0.445873527,0.666666630$' \
  || { echo "svf_at_points built against the installed package gave a wrong SVF" >&2; exit 1; }
echo "installed package: examples/svf_at_points built and checked"
# The configuration without the suites (-DSKYBAND_BUILD_TESTS=OFF) must configure and link: the
# benchmarks alone, in their own folder (the libraries' objects are ccache hits of the build above).
NOTESTS_DIR=${SKYBAND_NOTESTS_BUILD_DIR:-build-notests}
GEN=()
if [ ! -f "$NOTESTS_DIR/CMakeCache.txt" ] && command -v ninja >/dev/null; then GEN=(-G Ninja); fi
cmake -S . -B "$NOTESTS_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release -DSKYBAND_BUILD_TESTS=OFF \
      -DSKYBAND_BUILD_BENCH=ON -DSKYBAND_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build "$NOTESTS_DIR" -j "$(nproc)" --target skyband_benches
# Then the sanitizer checks: every fuzz harness briefly, and the parser, geometry and climate
# suites under ASan + UBSan with floating-point traps (scripts/ci-sanitizers.sh).
# SKYBAND_SKIP_SANITIZERS=1 skips them, for a quick local run.
if [ "${SKYBAND_SKIP_SANITIZERS:-0}" != 1 ]; then
  scripts/ci-sanitizers.sh
fi
