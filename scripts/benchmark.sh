#!/usr/bin/env bash
# Side-by-side benchmark (not part of the test suite): TetMesher vs TetGen vs Gmsh vs
# vtkDelaunay3D on the Data/ corpus. One command:
#   bash scripts/benchmark.sh [--quick] [--cases a,b,c] [--tools ...] [--timeout S] [--repeat N]
# Installs tetgen, gmsh, time and python3-matplotlib if missing (idempotent: dpkg is asked
# first), builds the CLI into build-bench/ (Release, -j2), then runs scripts/benchmark.py,
# which writes Testing/Benchmarks/results/corpus.{md,csv} and PNGs (corpus-partial.* for
# --quick/--cases).
#   bash scripts/benchmark.sh --mode sized [--cases a,b] [--fine a,b] [--tools ...]
# runs scripts/benchmark_sized.py instead: the full pipeline at a constant size h, TetMesher
# vs TetGen -q -a vs Gmsh, into Testing/Benchmarks/results/sized.{md,csv}.
#   bash scripts/benchmark.sh --mode given [--cases a,b] [--points N | --counts a,b] [--tools ...]
# runs scripts/benchmark_given.py: many given interior points (TetGen's -i), TetMesher
# --boundary-only --points vs TetGen -pYi, into Testing/Benchmarks/results/given.{md,csv}.
# BENCH_BUILD=dir builds and uses the CLI in dir instead of build-bench/.
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
missing=()
for p in tetgen gmsh time python3-matplotlib python3-vtk9 python3-numpy; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "benchmark: installing ${missing[*]}"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

BUILD="${BENCH_BUILD:-build-bench}"
if [ ! -f "$BUILD/build.ninja" ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF
fi
cmake --build "$BUILD" -j2 --target tetmesher

script=scripts/benchmark.py
if [ "${1:-}" = "--mode" ]; then
  case "${2:-}" in
    boundary) ;;
    sized) script=scripts/benchmark_sized.py ;;
    given) script=scripts/benchmark_given.py ;;
    *) echo "benchmark: --mode boundary|sized|given" >&2; exit 2 ;;
  esac
  shift 2
fi
exec /usr/bin/python3 "$script" --tetmesher "$BUILD/bin/tetmesher" "$@"
