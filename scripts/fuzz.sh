#!/usr/bin/env bash
# Builds the libFuzzer harnesses of fuzz/ (clang, ASan + UBSan, SKYBAND_FUZZ=ON) into their own
# build folder and runs each one for SECONDS.
#
# Usage: scripts/fuzz.sh SECONDS [TARGET...]     e.g. scripts/fuzz.sh 30, scripts/fuzz.sh 600 mesh_off
# TARGETs (default all): mesh_obj mesh_off mesh_ply mesh_stl mesh_cityjson mesh_cityjsonseq mesh_citygml
#   csv_table points_csv times_csv scene_file scene_override epw_reader weather_file (the executables are <build>/fuzz/fuzz_<TARGET>).
# Environment:
#   SKYBAND_FUZZ_BUILD_DIR  build folder (default build-fuzz)
#   SKYBAND_SHARED_DIR      the shared/ folder with data/ (default ../shared)
#   SKYBAND_FUZZ_JOBS       build parallelism (default 2: the machine is shared)
#   SKYBAND_FUZZ_KEEP_GOING=1  libFuzzer fork mode with -ignore_crashes/-ignore_timeouts/
#                           -ignore_ooms: keep fuzzing after a finding and save every one
#                           (default: each harness stops at its first finding, as libFuzzer does)
#
# Two phases per target:
#  1. Seed check: every seed runs once, each in its own process (-timeout=10, -rss_limit_mb=2048).
#     A seed that crashes, times out or runs out of memory is a finding (its reproducer is the
#     seed file itself) and is left out of phase 2, so that a known bad input does not stop the
#     fuzzer before it starts.
#  2. Fuzzing: -max_total_time=SECONDS -timeout=10 -rss_limit_mb=2048 on the corpora
#       <build>/fuzz/corpus/<target>/   (writable: what libFuzzer finds; kept between runs)
#       <build>/fuzz/seeds/<target>/    (generated each run: links to the seeds, see below)
#     Reproducers go to <build>/fuzz/findings/<target>/ (crash-*, timeout-*, oom-*, leak-*),
#     the output of each run to <build>/fuzz/logs/.
# Seeds, used in place (symbolic links; files over 256 KiB are cut to their first 64 KiB at a
# line end into the build folder, since big seeds only slow the fuzzer down):
#   ../shared/data/{buildings,cityjson,citygml,degenerate,weather,fuzz-found}, tests/data/meshes,
#   examples/scenes, and the hand-made fuzz/seeds/<target>/, chosen by file extension.
# Reproduce a finding: <build>/fuzz/fuzz_<target> <reproducer file>.
#
# Exit status: 0 if no harness reported anything, 1 if any seed or fuzzing run ended in a crash,
# sanitizer report, escaped exception, timeout, out-of-memory or leak (each is listed at the end
# with its reproducer), 2 on a usage or build error.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

ALL_TARGETS=(mesh_obj mesh_off mesh_ply mesh_stl mesh_cityjson mesh_cityjsonseq mesh_citygml csv_table points_csv times_csv scene_file scene_override epw_reader weather_file)
if [ $# -lt 1 ] || ! [[ "$1" =~ ^[0-9]+$ ]] || [ "$1" -lt 1 ]; then
  sed -n '2,9p' "$0" >&2
  exit 2
fi
FUZZ_SECONDS=$1
shift
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=("${ALL_TARGETS[@]}")
for t in "${TARGETS[@]}"; do
  [[ " ${ALL_TARGETS[*]} " == *" $t "* ]] || { echo "fuzz.sh: unknown target '$t' (targets: ${ALL_TARGETS[*]})" >&2; exit 2; }
done

BUILD_DIR=${SKYBAND_FUZZ_BUILD_DIR:-build-fuzz}
SHARED_DIR=$(realpath -m "${SKYBAND_SHARED_DIR:-$ROOT/../shared}")
JOBS=${SKYBAND_FUZZ_JOBS:-2}
LIBFUZZER_LIMITS=(-timeout=10 -rss_limit_mb=2048)

scripts/install-deps.sh --fuzz

# Build: libraries + harnesses only (the target skyband_fuzzers), Debug with -O1: assertions on,
# fast enough to fuzz. The tests are configured too (not built here): scripts/ci-sanitizers.sh
# builds a subset of them in the same folder, on the same sanitized libraries.
t0=$(date +%s)
if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  GEN=()
  command -v ninja >/dev/null && GEN=(-G Ninja)
  CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" -DSKYBAND_FUZZ=ON -DSKYBAND_BUILD_TESTS=ON -DSKYBAND_BUILD_BENCH=OFF \
    -DSKYBAND_SHARED_DIR="$SHARED_DIR" -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=TRUE || exit 2
fi
cmake --build "$BUILD_DIR" --target skyband_fuzzers -j "$JOBS" || exit 2
echo "fuzz.sh: build took $(( $(date +%s) - t0 )) s"
BUILD=$(realpath "$BUILD_DIR")
FUZZ_DIR=$BUILD/fuzz

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
# Third-party leaks on libcitygml's failure path (scripts/lsan-suppressions.txt).
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan-suppressions.txt}

# Extensions (lower case) of each target's seeds.
seed_extensions() {
  case "$1" in
    mesh_obj) echo obj ;;
    mesh_off) echo off ;;
    mesh_ply) echo ply ;;
    mesh_stl) echo stl ;;
    mesh_cityjson) echo json ;;
    mesh_cityjsonseq) echo jsonl ;;
    mesh_citygml) echo gml ;;
    csv_table | points_csv | times_csv) echo csv ;;
    scene_file) echo toml ;;
    scene_override) echo txt ;;  # only fuzz-found/scene_override_* among the shared files
    epw_reader) echo epw ;;
    weather_file) echo epw ;;  # and fuzz/seeds/weather_file/ (TMY3 CSV)
  esac
}

# Lists the candidate seed files of a target, one per line.
candidate_seeds() {
  local target=$1 ext dir f base
  ext=$(seed_extensions "$target")
  for dir in "$SHARED_DIR/data/buildings" "$SHARED_DIR/data/cityjson" "$SHARED_DIR/data/citygml" "$SHARED_DIR/data/degenerate" "$SHARED_DIR/data/weather" \
             "$SHARED_DIR/data/fuzz-found" "$ROOT/tests/data/meshes" "$ROOT/examples/scenes" "$ROOT/fuzz/seeds/$target"; do
    [ -d "$dir" ] || continue
    for f in "$dir"/*; do
      [ -f "$f" ] || continue
      base=$(basename "$f")
      [ "${base,,}" != "readme.md" ] || continue
      if [ "$dir" = "$ROOT/fuzz/seeds/$target" ] || [[ "${base,,}" == *."$ext" ]]; then
        if [ "$target" = scene_override ] && [ "$dir" != "$ROOT/fuzz/seeds/$target" ] && [[ "$base" != scene_override* ]]; then
          continue
        fi
        echo "$f"
      fi
    done
  done
}

# What a libFuzzer log reports, in a few words.
classify_raw() {
  local log=$1
  if grep -q "skyband-fuzz: FINDING" "$log"; then grep -m1 "skyband-fuzz: FINDING" "$log" | sed 's/^skyband-fuzz: FINDING: //' | cut -c1-300
  elif grep -q "ERROR: libFuzzer: timeout" "$log"; then echo "timeout (> 10 s)"
  elif grep -q "ERROR: libFuzzer: out-of-memory" "$log"; then grep -m1 "ERROR: libFuzzer: out-of-memory" "$log" | sed 's/.*ERROR: libFuzzer: //'
  elif grep -q "ERROR: LeakSanitizer" "$log"; then echo "memory leak"
  elif grep -q "runtime error:" "$log"; then grep -m1 "runtime error:" "$log" | cut -c1-300
  elif grep -q "ERROR: AddressSanitizer" "$log"; then grep -m1 "ERROR: AddressSanitizer" "$log" | sed 's/.*ERROR: AddressSanitizer: //' | cut -c1-200
  elif grep -qE "Assertion .* failed" "$log"; then grep -m1 -oE "[^ ]+: Assertion .* failed" "$log" | cut -c1-300
  elif grep -q "terminate called" "$log"; then grep -m1 -A1 "terminate called" "$log" | tr '\n' ' ' | cut -c1-300
  elif grep -q "ERROR: libFuzzer: deadly signal" "$log"; then echo "deadly signal"
  else echo "libFuzzer exit status $2 (see the log)"
  fi
}

classify() { classify_raw "$@" | tr '|' '/'; }  # '|' separates the summary's columns

# The first stack frame in skyband's own code (or the first frame at all), for the summary.
where_in_code() {
  local frame
  frame=$(grep -E "^ +#[0-9]+ " "$1" | grep -E "$ROOT/(io|geometry|lighting|fuzz)/" | grep -v "fuzz_support.h" | head -1 || true)
  [ -n "$frame" ] || frame=$(grep -E "^ +#[0-9]+ " "$1" | grep -vE "libFuzzer|compiler-rt|sanitizer|asan_|ubsan_|libc\.so|__cxa_|abort" | head -1 || true)
  # "#3 0x55… in ns::f(args) /path/file.cpp:12:5" -> "ns::f file.cpp:12:5"
  echo "$frame" | sed -E 's/^ +#[0-9]+ 0x[0-9a-f]+ in //; s/\(anonymous namespace\)/{anon}/g; s#'"$ROOT"'/##' |
    awk '{ loc = $NF; name = $0; sub(/ [^ ]*$/, "", name); sub(/\(.*/, "", name); print name, loc }' | cut -c1-200
}

mkdir -p "$FUZZ_DIR/logs"
FINDINGS=()   # "target | what | where | reproducer"
for target in "${TARGETS[@]}"; do
  exe=$FUZZ_DIR/fuzz_$target
  seeds=$FUZZ_DIR/seeds/$target corpus=$FUZZ_DIR/corpus/$target findings=$FUZZ_DIR/findings/$target
  rm -rf "$seeds" "$FUZZ_DIR/logs/$target"
  mkdir -p "$seeds" "$corpus" "$findings" "$FUZZ_DIR/logs/$target"

  # Phase 1: seed check.
  n_seeds=0 n_bad=0
  while IFS= read -r f; do
    base=$(basename "$f")
    origin=$(basename "$(dirname "$f")")
    link="$seeds/$origin--$base"
    if [ "$(stat -c %s "$f")" -gt 262144 ]; then
      link="$link.head64k"
      head -c 65536 "$f" | sed '$d' > "$link"   # drop the cut last line
    else
      ln -s "$f" "$link"
    fi
    log=$FUZZ_DIR/logs/$target/seed--$origin--$base.log
    set +e
    "$exe" "${LIBFUZZER_LIMITS[@]}" -runs=1 "$link" > "$log" 2>&1
    rc=$?
    set -e
    n_seeds=$((n_seeds + 1))
    if [ $rc -ne 0 ]; then
      n_bad=$((n_bad + 1))
      rm -f "$link"
      known=""
      [ "$origin" = fuzz-found ] && known=" [known: ../shared/data/fuzz-found/README.md]"
      FINDINGS+=("$target | seed: $(classify "$log" $rc) | $(where_in_code "$log") | $f$known | log $log")
    fi
  done < <(candidate_seeds "$target")
  echo "fuzz.sh: $target: $n_seeds seeds, $n_bad failing (left out of the corpus)"

  # Phase 2: fuzzing.
  log=$FUZZ_DIR/logs/$target/fuzz.log
  opts=("${LIBFUZZER_LIMITS[@]}" -max_total_time="$FUZZ_SECONDS" -print_final_stats=1 -artifact_prefix="$findings/")
  if [ "${SKYBAND_FUZZ_KEEP_GOING:-0}" = 1 ]; then
    opts+=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  fi
  before=$(find "$findings" -type f | sort)
  echo "fuzz.sh: $target: fuzzing for $FUZZ_SECONDS s (log: $log)"
  set +e
  # -fork: the children run in the build folder's logs folder (fuzz-N.log files land there).
  (cd "$FUZZ_DIR/logs/$target" && "$exe" "${opts[@]}" "$corpus" "$seeds") > "$log" 2>&1
  rc=$?
  set -e
  new=$(comm -13 <(echo "$before") <(find "$findings" -type f | sort) | sed '/^$/d')
  if [ $rc -ne 0 ] && [ -z "$new" ]; then
    FINDINGS+=("$target | fuzzing: $(classify "$log" $rc) | $(where_in_code "$log") | (no reproducer written) | log $log")
  fi
  # Each reproducer runs once more on its own, so that every finding (also in fork mode, where
  # the parent's log holds no stacks) is described from its own log.
  while IFS= read -r a; do
    [ -n "$a" ] || continue
    alog=$FUZZ_DIR/logs/$target/$(basename "$a").log
    set +e
    "$exe" "${LIBFUZZER_LIMITS[@]}" -runs=1 "$a" > "$alog" 2>&1
    arc=$?
    set -e
    what=$(classify "$alog" $arc)
    [ $arc -ne 0 ] || what="$(basename "$a" | cut -d- -f1) (does not reproduce on its own)"
    FINDINGS+=("$target | fuzzing: $what | $(where_in_code "$alog") | $a | log $alog")
  done <<< "$new"
  grep -E "^stat::number_of_executed_units|^#[0-9]+.*DONE" "$log" | tail -1 | sed "s/^/fuzz.sh: $target: /" || true
done

echo
if [ ${#FINDINGS[@]} -eq 0 ]; then
  echo "fuzz.sh: no findings (${TARGETS[*]}; $FUZZ_SECONDS s each)"
  exit 0
fi
echo "fuzz.sh: ${#FINDINGS[@]} finding(s): target | what | where | reproducer | log"
printf '  %s\n' "${FINDINGS[@]}"
echo "fuzz.sh: distinct (count | target | what | where):"
printf '%s\n' "${FINDINGS[@]}" | cut -d'|' -f1-3 | sed -E 's/ *$//' | sort | uniq -c | sed 's/^/  /'
echo "Reproduce: $FUZZ_DIR/fuzz_<target> <reproducer>"
exit 1
