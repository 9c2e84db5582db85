#!/usr/bin/env bash
# Starts the real ParaView GUI under Xvfb with the TetMesher plugin and a script that meshes a
# surface, cuts it and saves a screenshot; then compares the screenshot with the baseline.
# Usage: RunGuiTest.sh PARAVIEW PVPYTHONPATH PLUGIN SURFACE BASELINE WORK_DIR
set -euo pipefail
paraview="$1" pvpath="$2" plugin="$3" surface="$4" baseline="$5" work="$6"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mkdir -p "$work"
shot="$work/GuiCutMesh.png"
rm -f "$shot"
TETMESHER_PLUGIN="$plugin" TETMESHER_SURFACE="$surface" TETMESHER_SCREENSHOT="$shot" \
  PYTHONPATH="$pvpath" timeout 300 xvfb-run -a -s "-screen 0 1280x1024x24" \
  "$paraview" --script="$here/../Python/GuiCutMesh.py" --exit > "$work/paraview.log" 2>&1 || true
if [ ! -s "$shot" ]; then
  echo "ParaView did not write the screenshot; its output:"
  cat "$work/paraview.log"
  exit 1
fi
/usr/bin/python3 "$here/CompareImages.py" "$shot" "$baseline"
