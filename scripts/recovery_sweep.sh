#!/usr/bin/env bash
# Boundary recovery alone, over many surfaces (a benchmark, not a test): for each surface the
# boundary mesh's Steiner points and its "boundary recovery" stage time (`--timings`), then the
# totals. Compare two builds by running it with each binary in turn, nothing else running.
#   bash scripts/recovery_sweep.sh TETMESHER [SURFACE...]
# Default surfaces: Data/*.off, Data/*.vtp and TetGen's test models in ../shared/peer-tests/
# (where present). A surface that is not meshed counts as such in the totals.
set -uo pipefail
cd "$(dirname "$0")/.."
bin="$1"
shift
files=("$@")
if [ ${#files[@]} -eq 0 ]; then
  files=(Data/*.off Data/*.vtp ../shared/peer-tests/tetgentests-cgal/*.off
    ../shared/peer-tests/tetgentests-meshlab/*.off)
fi
out=$(mktemp -d)
meshed=0 failed=0 steiner=0 seconds=0
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  log=$("$bin" mesh "$f" -o "$out/mesh.vtu" -q --boundary-only --timings 2>&1)
  if [ $? -eq 0 ]; then
    st=$(grep -o "[0-9]* Steiner" <<<"$log" | head -1 | cut -d' ' -f1)
    rt=$(awk '/boundary recovery/ {print $1}' <<<"$log")
    printf '%-40s %5s Steiner %8s s recovery\n' "$(basename "$f")" "$st" "$rt"
    meshed=$((meshed + 1))
    steiner=$((steiner + st))
    seconds=$(awk -v a="$seconds" -v b="$rt" 'BEGIN {print a + b}')
  else
    printf '%-40s not meshed\n' "$(basename "$f")"
    failed=$((failed + 1))
  fi
done
rm -rf "$out"
echo "meshed $meshed, not meshed $failed, Steiner points $steiner, recovery $seconds s"
