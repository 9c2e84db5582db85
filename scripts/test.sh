#!/usr/bin/env bash
# Runs every test of TetMesher on a fresh Debian 12 machine: installs what is missing,
# builds, then ctest (C++ core and VTK tests, image regression under Xvfb, Python, pvpython
# plugin, command line, installed consumer project).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh"
/usr/bin/python3 "$root/Testing/Data/make_test_meshes.py" --check
bash "$root/scripts/build.sh"
cd "$root/build"
xvfb-run -a -s "-screen 0 1024x768x24" ctest --output-on-failure -j "${TETMESHER_JOBS:-$(nproc)}" "$@"
