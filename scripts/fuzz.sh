#!/bin/bash
# Fuzz the core (diagnosis + mesher) with libFuzzer, ASan and UBSan.
#
#   scripts/fuzz.sh [SECONDS] [extra libFuzzer options...]     (default 600 s)
#
# Builds Testing/Fuzz standalone with clang into build-fuzz/ (core only, no VTK), makes the
# seed corpus from Data/ surfaces and Testing/Data/defects/ (Testing/Fuzz/make_seeds.py) plus
# the stored regressions (Testing/Fuzz/regressions/), and
# runs FuzzSurface on build-fuzz/corpus (kept between runs) with -timeout=10 (a hang is an
# input that takes more than 10 s). Crashes, hangs (timeout-*) and leaks land in
# build-fuzz/artifacts/; replay one with `build-fuzz/FuzzSurface FILE`, then add it to
# Testing/Core/TestFuzzRegressions.cxx. Environment: FUZZ_JOBS (fuzzing processes in fork
# mode, default 1), FUZZ_BUILD_DIR (default build-fuzz).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
build=${FUZZ_BUILD_DIR:-build-fuzz}
jobs=${FUZZ_JOBS:-1}

if ! command -v clang++ >/dev/null; then
  echo "fuzz.sh: clang++ is needed (apt-get install clang)" >&2
  exit 2
fi
core_dir=$PWD/Filters/Core
if [ -n "${FUZZ_REV:-}" ]; then
  rev=$(git rev-parse --verify "$FUZZ_REV^{commit}")
  case "$build" in /*) core_dir=$build/core-src/Filters/Core ;; *) core_dir=$PWD/$build/core-src/Filters/Core ;; esac
  rm -rf "$build/core-src" && mkdir -p "$build/core-src"
  git archive "$rev" Filters/Core | tar -x -C "$build/core-src"
  echo "fuzz.sh: fuzzing Filters/Core of $rev"
fi
cmake -S Testing/Fuzz -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTETMESHER_CORE_SOURCE_DIR="$core_dir" >/dev/null
cmake --build "$build" -j2 --target FuzzSurface

mkdir -p "$build/corpus" "$build/seeds" "$build/artifacts"
# Data/u.off is left out: 1.4 s to mesh in Release, over 10 s under ASan (a "hang").
surfaces=(Data/sphere.off Data/cube.vtp Data/cubes.off Data/star.off Data/step.off
  Data/hole.off Data/blob-closed.off Data/icosphere.vtp Data/invalid/mpi.off)
shopt -s nullglob
surfaces+=(Testing/Data/defects/*.off)
python=python3
[ -x /usr/bin/python3 ] && python=/usr/bin/python3  # Debian's, with vtkmodules for .vtp
"$python" Testing/Fuzz/make_seeds.py "$build/seeds" "${surfaces[@]}"
# The stored regressions are seeds too: a run then also replays every input that once
# crashed or hung, so a clean run says they stay fixed under the fuzzer's own build.
cp Testing/Fuzz/regressions/*.bin "$build/seeds/"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Fork mode keeps fuzzing after a crash or a hang, so that one run collects all of them.
parallel=(-fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
start=$(date +%s)
status=0
"$build/FuzzSurface" "$build/corpus" "$build/seeds" \
  -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -max_len=200000 \
  -print_final_stats=1 -artifact_prefix="$build/artifacts/" \
  ${parallel[@]+"${parallel[@]}"} "$@" || status=$?
echo "fuzz.sh: ran $(( $(date +%s) - start )) s, status $status; artifacts:"
ls -la "$build/artifacts"
exit $status
