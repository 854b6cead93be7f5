#!/usr/bin/env bash
# Configures and builds skyband (Release) into ./build (or $SKYBAND_BUILD_DIR).
# Usage: scripts/build.sh [extra cmake args] — applied to an existing build folder too.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache keys on paths relative to the repository (build folders and clones share objects).
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
BUILD_DIR=${SKYBAND_BUILD_DIR:-build}
GEN=()
command -v ninja >/dev/null && GEN=(-G Ninja)
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
elif [ "$#" -gt 0 ]; then
  # An existing cache keeps its generator and build type; the extra arguments are applied to it.
  cmake -S . -B "$BUILD_DIR" "$@"
fi
cmake --build "$BUILD_DIR" -j "$(nproc)"
