#!/usr/bin/env bash
# Installs the build tree into a fresh prefix, builds a consumer project against the
# installed CMake package, and runs it. Usage: RunConsumer.sh BUILD_DIR CONSUMER_SRC WORK_DIR
set -euo pipefail
build="$1" source="$2" work="$3"
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work.install.log" 2>&1 || { cat "$work.install.log"; exit 1; }
cmake -S "$source" -B "$work/build" -DTetMesher_DIR="$work/prefix/lib/cmake/TetMesher" > "$work.configure.log" 2>&1 || { cat "$work.configure.log"; exit 1; }
cmake --build "$work/build" > "$work.build.log" 2>&1 || { cat "$work.build.log"; exit 1; }
# The consumer must run from the install tree, not the build tree.
"$work/build/consumer"
ldd "$work/build/consumer" > "$work.ldd.txt"
grep -q "$work/prefix/lib/libvtkFiltersTetMesher" "$work.ldd.txt" || { echo "consumer is not linked to the installed library"; cat "$work.ldd.txt"; exit 1; }
# The installed command line: the lean path, then `quality`, which needs VTK (the static
# executable's dynamic twin in libexec, or the module in lib).
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$work/tet.off"
"$work/prefix/bin/tetmesher" mesh "$work/tet.off" -o "$work/tet.vtu" -q
"$work/prefix/bin/tetmesher" quality "$work/tet.vtu" > "$work.quality.txt" 2>&1 || { echo "installed tetmesher quality failed"; cat "$work.quality.txt"; exit 1; }
grep -q "1 tetrahedra, 4 points" "$work.quality.txt" || { echo "installed tetmesher quality:"; cat "$work.quality.txt"; exit 1; }
echo "consumer project: ok"
