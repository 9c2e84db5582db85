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
echo "consumer project: ok"
