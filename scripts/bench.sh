#!/usr/bin/env bash
# Builds skyband in Release and runs every benchmark (bench_*), each printing its own table.
# Usage: scripts/bench.sh [--quick]   (--quick is passed to the benchmarks whose --help offers it)
# SKYBAND_BUILD_DIR selects the build folder (default: build-bench, always Release).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --bench
BUILD_DIR=${SKYBAND_BUILD_DIR:-build-bench}
GEN=()
command -v ninja >/dev/null && GEN=(-G Ninja)
cmake -S . -B "$BUILD_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release -DSKYBAND_BUILD_BENCH=ON >/dev/null
# Build only the benchmarks (and what they link), not every test.
mapfile -t targets < <(for f in bench/*_bench.cpp; do n=$(basename "$f" _bench.cpp); echo "bench_$n"; done)
if [ "${#targets[@]}" -eq 0 ]; then
  echo "no benchmarks found in bench/" >&2
  exit 1
fi
cmake --build "$BUILD_DIR" -j "$(nproc)" --target "${targets[@]}"
status=0
for t in "${targets[@]}"; do
  exe="$BUILD_DIR/bench/$t"
  args=()
  if [ "${1:-}" = "--quick" ] && "$exe" --help 2>/dev/null | grep -q -- "--quick"; then args=(--quick); fi
  echo "=== $t ${args[*]:-} ==="
  "$exe" "${args[@]}" || { echo "$t failed" >&2; status=1; }
done
exit $status
