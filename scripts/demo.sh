#!/usr/bin/env bash
# The main job on an embedded default: builds TetMesher (installing what is missing) and
# prints the quality report of a shipped tetrahedral mesh. Pass another mesh to report on it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/setup.sh" >/dev/null
bash "$root/scripts/build.sh" >/dev/null
"$root/build/bin/tetmesher" quality "${1:-$root/Testing/Data/jittered-cube.vtu}" --histogram
