#!/usr/bin/env bash
# The main job on an embedded default: builds TetMesher (installing what is missing), meshes
# Data/torus.vtp and prints the one-line summary and the quality report. Pass another
# surface (and options) to mesh that instead.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh" >/dev/null
bash "$root/scripts/build.sh" >/dev/null
out="${TMPDIR:-/tmp}/tetmesher-demo.vtu"
if [ "$#" -eq 0 ]; then
  set -- "$root/Data/torus.vtp"
fi
"$root/build/bin/tetmesher" mesh "$@" -o "$out" --stats
echo "mesh written to $out (open it in ParaView)"
