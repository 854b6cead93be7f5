#!/usr/bin/env bash
# The sanitizer checks of the test command (scripts/test.sh), in one clang build with ASan +
# UBSan (build-fuzz: the libraries are compiled once for both):
#  1. every libFuzzer harness of fuzz/ for SKYBAND_CI_FUZZ_SECONDS seconds (default 5) after its
#     seed check (scripts/fuzz.sh): a crash, sanitizer report, timeout or out-of-memory fails;
#  2. a subset of the suite under the sanitizers with floating-point traps (FE_INVALID,
#     FE_DIVBYZERO; scripts/test-sanitized.sh): the parsers (io.*), the geometry core
#     (geometry.*, but for horizon_real_meshes: 2 min alone under ASan) and the climate chain
#     (lighting: sun, Perez sky, weather, daylight coefficients, column tables, point
#     irradiance). The whole suite under the sanitizers takes ~35 min from a
#     fresh folder on the 2-core CI machine (scripts/test-sanitized.sh, run by hand); this subset
#     keeps CI under 30 min in all.
# Usage: scripts/ci-sanitizers.sh
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$(date +%s)
scripts/fuzz.sh "${SKYBAND_CI_FUZZ_SECONDS:-5}"
t1=$(date +%s)
SKYBAND_SANITIZE_BUILD_DIR=${SKYBAND_FUZZ_BUILD_DIR:-build-fuzz} \
SKYBAND_SANITIZE_EXCLUDE='^geometry\.horizon_real_meshes$' \
SKYBAND_SANITIZE_TESTS='^(io|geometry)\.|^lighting\.(sun_position|perez_sky|perez_efficacy|perez_transposition|weather_timing|moment_series|climate_irradiation|daylight_coefficients|sky_column_table|sky_radiance_grid|point_irradiance)$' \
  scripts/test-sanitized.sh
echo "ci-sanitizers: fuzzing $((t1 - t0)) s, sanitized suites $(( $(date +%s) - t1 )) s"
