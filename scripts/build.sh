#!/usr/bin/env bash
# Configures and builds TetMesher: build/ against Debian's VTK 9.1 (module, Python package,
# CLI, tests) and build-pv/ (the ParaView 5.11 plugin, with ParaView's own VTK 9.2).
# Run scripts/setup.sh first (scripts/test.sh and scripts/demo.sh do).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PV_PREFIX="${TETMESHER_PV_PREFIX:-/opt/tetmesher-paraview}"
jobs="${TETMESHER_JOBS:-$(nproc)}"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

pv_dir="$PV_PREFIX/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11"
if [ ! -f "$root/build-pv/CMakeCache.txt" ]; then
  cmake -S "$root/Plugin" -B "$root/build-pv" "${generator[@]}" -DParaView_DIR="$pv_dir" >/dev/null
fi
cmake --build "$root/build-pv" -j "$jobs"

if [ ! -f "$root/build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$root/build" "${generator[@]}" \
    -DTETMESHER_PARAVIEW_PLUGIN="$root/build-pv/lib/paraview-plugins/TetMesher/TetMesher.so" \
    -DTETMESHER_PVPYTHON="$PV_PREFIX/usr/bin/pvpython" \
    -DTETMESHER_PVPYTHON_PATH="$PV_PREFIX/usr/lib/python3/dist-packages" >/dev/null
fi
cmake --build "$root/build" -j "$jobs"
