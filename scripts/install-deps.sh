#!/usr/bin/env bash
# Installs the Debian packages skyband builds against, only those that are missing.
# Why each one is in the README. Usage: scripts/install-deps.sh [--bench] [--fuzz]
# (--bench: also Embree, which only the Monte Carlo baseline benchmark uses;
#  --fuzz: also clang with libFuzzer and its sanitizer runtimes, for scripts/fuzz.sh — about
#  350 MB, so not in the default list. scripts/test-sanitized.sh needs nothing extra: GCC's
#  libasan/libubsan come with build-essential.)
set -euo pipefail
PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  libcgal-dev libgmp-dev libmpfr-dev      # exact predicates, polygon triangulation
  libeigen3-dev                           # small fixed-size vectors and matrices
  libopenmesh-dev                         # mesh readers (OBJ, OFF, PLY, STL)
  libopenexr-dev                          # HDR output
  libpng-dev                              # tone-mapped previews
  libboost-test-dev                       # Boost.Test
  libtbb-dev                              # parallel_for over query points and pixels
  libcli11-dev                            # command-line parsing
  nlohmann-json3-dev                      # --json output, reports
  libtomlplusplus-dev                     # scene files
  libsimdjson-dev                         # CityJSON / CityJSONSeq input (on-demand, correctly rounded)
  libhowardhinnant-date-dev tzdata        # named time zones (IANA tz database) for moments
  libnetcdf-dev                           # hourly results (NetCDF-4, CF conventions)
  libcitygml-dev libxerces-c-dev          # CityGML 1.0/2.0 input (libcitygml parses with Xerces-C)
  libproj-dev proj-data                   # geographic city models (PLATEAU) projected to UTM
  libgdal-dev                             # DSM rasters in, GeoTIFF maps out (skyband map)
  clang-format                            # the layout check of the sources (scripts/check-format.sh)
)
for arg in "$@"; do
  case "$arg" in
    --bench) PACKAGES+=(libembree-dev) ;;                # bench_sky_vs_monte_carlo's baseline
    --fuzz) PACKAGES+=(clang libclang-rt-dev llvm) ;;    # clang++, libFuzzer + ASan/UBSan runtimes
                                                         # (not pulled in without recommends),
                                                         # llvm-symbolizer for readable stacks
    *) echo "install-deps: unknown option '$arg' (options: --bench, --fuzz)" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
