#!/usr/bin/env bash
# The README's main command: install what is missing, build, and run the main job on the
# built-in default scene — the paper's figures (Fig. 5a–d materials, Fig. 6a–d solar altitudes)
# into ./figures, after the sky-view-factor and irradiance demo tables.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
BUILD_DIR=${SKYBAND_BUILD_DIR:-build}
"$BUILD_DIR/cli/skyband" svf --demo
echo
"$BUILD_DIR/cli/skyband" irradiance --demo --sun-altitude 35 --sun-azimuth 200
echo
"$BUILD_DIR/cli/skyband" figures --out "${1:-figures}"
