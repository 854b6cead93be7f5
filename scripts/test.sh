#!/usr/bin/env bash
# The README's test command: install what is missing, build, run every test, then the
# sanitizer checks.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
BUILD_DIR=${SKYBAND_BUILD_DIR:-build}
(cd "$BUILD_DIR" && ctest --output-on-failure -j "$(nproc)" --timeout 900)
# Then the sanitizer checks: every fuzz harness briefly, and the parser, geometry and climate
# suites under ASan + UBSan with floating-point traps (scripts/ci-sanitizers.sh).
# SKYBAND_SKIP_SANITIZERS=1 skips them, for a quick local run.
if [ "${SKYBAND_SKIP_SANITIZERS:-0}" != 1 ]; then
  scripts/ci-sanitizers.sh
fi
