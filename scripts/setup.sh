#!/usr/bin/env bash
# Installs everything TetMesher needs on a fresh Debian 12 machine. Idempotent: packages
# already present are not fetched again, the pvpython prefix is built once.
#
# Why the private ParaView prefix: python3-paraview (pvpython) conflicts with python3-vtk9
# (needed by libvtk9-dev), and ParaView's CMake config wants python3-paraview's files. We
# unpack python3-paraview into $TETMESHER_PV_PREFIX and mirror the system dirs around it
# (see shared notes, build-on-debian.md).
set -euo pipefail

PV_PREFIX="${TETMESHER_PV_PREFIX:-/opt/tetmesher-paraview}"
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi

packages=(
  build-essential cmake ninja-build pkg-config git clang-format
  libvtk9-dev python3-vtk9 python3-numpy
  paraview paraview-dev qtbase5-dev qttools5-dev libqt5svg5-dev qtxmlpatterns5-dev-tools libqt5opengl5-dev
  libgtest-dev libgmp-dev xvfb xauth
  tetgen gmsh libcgal-dev libtbb-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# pvpython in a private prefix, beside python3-vtk9.
stamp="$PV_PREFIX/.tetmesher-prefix-ok"
libdir=/usr/lib/x86_64-linux-gnu
if [ ! -f "$stamp" ]; then
  echo "setup: unpacking python3-paraview into $PV_PREFIX"
  tmp="$(mktemp -d)"
  chmod 755 "$tmp"
  if ! (cd "$tmp" && apt-get download python3-paraview >/dev/null 2>&1); then
    $SUDO apt-get update -q # no package lists yet on this machine
    (cd "$tmp" && apt-get download python3-paraview >/dev/null)
  fi
  $SUDO rm -rf "$PV_PREFIX"
  $SUDO mkdir -p "$PV_PREFIX"
  $SUDO dpkg -x "$tmp"/python3-paraview_*.deb "$PV_PREFIX"
  rm -rf "$tmp"
  # ParaView's CMake targets compute their prefix from the file's location: a real copy.
  $SUDO mkdir -p "$PV_PREFIX$libdir/cmake"
  $SUDO cp -r "$libdir/cmake/paraview-5.11" "$PV_PREFIX$libdir/cmake/"
  $SUDO touch "$stamp"
fi
# Mirror the system dirs around it (every run: packages installed later appear too).
mirror() { # mirror SRC DST: symlink every entry of SRC into DST unless DST has it already
  $SUDO mkdir -p "$2"
  for entry in "$1"/* "$1"/.[!.]*; do
    [ -e "$entry" ] || [ -L "$entry" ] || continue
    name="$(basename "$entry")"
    [ -e "$2/$name" ] || [ -L "$2/$name" ] || $SUDO ln -s "$entry" "$2/$name"
  done
}
mirror "$libdir/cmake" "$PV_PREFIX$libdir/cmake"
mirror "$libdir" "$PV_PREFIX$libdir"
mirror /usr/bin "$PV_PREFIX/usr/bin"
mirror /usr/share "$PV_PREFIX/usr/share"
[ -e "$PV_PREFIX/usr/include" ] || $SUDO ln -s /usr/include "$PV_PREFIX/usr/include"
echo "setup: ok (pvpython prefix $PV_PREFIX)"
