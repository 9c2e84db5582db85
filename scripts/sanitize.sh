#!/bin/bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (TETMESHER_SANITIZE=ON),
# for CI:
#
#   scripts/sanitize.sh          # core: VTK-free core + every core test      (build-asan-core/)
#   scripts/sanitize.sh vtk      # also the VTK module and its C++ tests      (build-asan/)
#   scripts/sanitize.sh all      # both
#   scripts/sanitize.sh threads  # the two-thread insertion's tests under ThreadSanitizer (build-tsan/)
#
# Any sanitizer report fails the test that hit it (halt_on_error, also for UBSan). Leak
# checking is on. Python and pvpython tests are not run here: their interpreters are not
# instrumented (LD_PRELOAD of libasan into them reports the interpreter's own leaks).
# Environment: SANITIZE_JOBS (build jobs, default 2), CTEST_ARGS (extra ctest arguments).
# Prints the time of every build and test phase.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-core}
jobs=${SANITIZE_JOBS:-2}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1}
timings=()

phase() { # name command...
  local name=$1 start status=0
  shift
  start=$(date +%s)
  echo "== sanitize.sh: $name"
  "$@" || status=$?
  timings+=("$(printf '%-40s %5d s%s' "$name" $(( $(date +%s) - start )) \
    "$([ $status -eq 0 ] || echo "  FAILED ($status)")")")
  return $status
}

report() {
  echo "== sanitize.sh: timings"
  printf '%s\n' "${timings[@]}"
}
trap report EXIT

core() {
  local b=build-asan-core
  phase "configure core" cmake -S . -B $b -DTETMESHER_CORE_ONLY=ON -DTETMESHER_SANITIZE=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  phase "build core + core tests" cmake --build $b -j"$jobs"
  phase "core tests (ASan+UBSan)" ctest --test-dir $b --output-on-failure -j1 ${CTEST_ARGS:-}
}

vtk() {
  local b=build-asan
  phase "configure VTK build" cmake -S . -B $b -DTETMESHER_SANITIZE=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_TESTING=ON >/dev/null
  phase "build VTK module, CLI, tests" cmake --build $b -j"$jobs"
  # The C++ executables: core tests and the module's C++ tests (TestTetQuality, ...).
  # CLI.Defects loads the instrumented module into Python: its CLI part is run on its own.
  local xvfb=()
  command -v xvfb-run >/dev/null && xvfb=(xvfb-run -a)
  phase "VTK C++ and CLI tests (ASan+UBSan)" ${xvfb[@]+"${xvfb[@]}"} ctest --test-dir $b \
    --output-on-failure -j1 -E '^(Python|Docs|ParaView|Install)\.|^CLI\.Defects$' ${CTEST_ARGS:-}
  phase "defect files through the CLI" /usr/bin/python3 Testing/Integration/TestDefects.py \
    --cli-only $b/bin/tetmesher Testing/Data/defects
}

# The kernel and the refinement insert large rounds, and the optimiser works large passes, on two
# threads that must never touch the same tets; the size floor's index is built in halves; the
# mesh job diagnoses the input beside the Delaunay (whose two halves share the perturbation
# order): any data race fails the test that hit it.
threads() {
  local b=build-tsan
  phase "configure core (TSan)" cmake -S . -B $b -DTETMESHER_CORE_ONLY=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS=-fsanitize=thread \
    -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread >/dev/null
  phase "build kernel tests (TSan)" cmake --build $b -j"$jobs" --target CoreTestDelaunayHalves \
    CoreTestLatticeHalves CoreTestOptimizerHalves CoreTestEdgeGraph \
    CoreTestDelaunay CoreTestSurfaceMeshing CoreTestPerturbationOrder CoreTestSizeField
  phase "two-thread tests (TSan)" ctest --test-dir $b \
    --output-on-failure -j1 -R 'Core\.Test(Delaunay|LatticeHalves|OptimizerHalves|EdgeGraph|SurfaceMeshing|PerturbationOrder|SizeField)' ${CTEST_ARGS:-}
}

case $what in
  core) core ;;
  vtk) vtk ;;
  all) core && vtk ;;
  threads) threads ;;
  *) echo "usage: $0 [core|vtk|all|threads]" >&2; exit 2 ;;
esac
