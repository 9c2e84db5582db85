#!/usr/bin/env bash
# Fetches larger real surfaces for TetMesher's tests and benchmarks from Debian packages into a
# cache folder (never into the repository's tracked files). Idempotent: packages already
# downloaded and unpacked are not fetched again.
#
#   scripts/fetch_corpus.sh [CACHE_DIR]        (default: <repo>/cache/corpus, git-ignored)
#   TETMESHER_DIAGNOSE=<CoreTestSurfaceDiagnosis executable> scripts/fetch_corpus.sh
#       also runs the input diagnosis on every fetched surface and writes
#       CACHE_DIR/diagnosis.txt (which files are valid mesher input).
#
# Result: CACHE_DIR/surfaces/<source>/<name>.{off,stl}, the same as links
# CACHE_DIR/all/<source>_<name> (for scripts/benchmark.py --data CACHE_DIR/all) and
# CACHE_DIR/MANIFEST.tsv (source, file, bytes, licence). Sources (Debian 12 packages; see Data/README.md):
#   libcgal-demo  data/meshes/*.off|*.stl from CGAL's data.tar.gz (about 150 files, 39 MB)
#   gmsh-doc      the .stl demos and tutorial data (gunzipped)
#   netgen-doc    the .stl examples (hinge, part1)
# Needs apt-get (apt lists up to date: run `apt-get update` once if a download fails) and
# dpkg-deb; no root needed for the download itself.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cache="${1:-$root/cache/corpus}"
mkdir -p "$cache/debs" "$cache/pkgs" "$cache/surfaces"
cache="$(cd "$cache" && pwd)"

packages=(libcgal-demo gmsh-doc netgen-doc)

fetch() {
  local pkg="$1"
  local stamp="$cache/pkgs/$pkg.done"
  [[ -f "$stamp" ]] && return 0
  (
    cd "$cache/debs"
    rm -f "$pkg"_*.deb
    if ! apt-get download "$pkg" >/dev/null 2>&1; then
      echo "apt-get download $pkg failed (try: apt-get update)" >&2
      exit 1
    fi
  )
  rm -rf "$cache/pkgs/$pkg"
  mkdir -p "$cache/pkgs/$pkg"
  dpkg-deb -x "$cache/debs/$pkg"_*.deb "$cache/pkgs/$pkg"
  touch "$stamp"
}

for pkg in "${packages[@]}"; do
  fetch "$pkg"
done

# CGAL: surfaces of data/meshes from the data tarball.
if [[ ! -f "$cache/surfaces/cgal.done" ]]; then
  rm -rf "$cache/surfaces/cgal" "$cache/tmp-cgal"
  mkdir -p "$cache/surfaces/cgal" "$cache/tmp-cgal"
  tar -xzf "$cache/pkgs/libcgal-demo/usr/share/doc/libcgal-dev/data.tar.gz" -C "$cache/tmp-cgal" \
    --wildcards 'data/meshes/*.off' 'data/meshes/*.stl'
  find "$cache/tmp-cgal/data/meshes" -maxdepth 1 -type f \( -name '*.off' -o -name '*.stl' \) \
    -exec mv -t "$cache/surfaces/cgal" {} +
  rm -rf "$cache/tmp-cgal"
  touch "$cache/surfaces/cgal.done"
fi

# Gmsh: .stl and .stl.gz anywhere in the documentation.
if [[ ! -f "$cache/surfaces/gmsh.done" ]]; then
  rm -rf "$cache/surfaces/gmsh"
  mkdir -p "$cache/surfaces/gmsh"
  while IFS= read -r -d '' f; do
    name="$(basename "$f")"
    case "$name" in
      *.gz) gzip -dc "$f" >"$cache/surfaces/gmsh/${name%.gz}" ;;
      *) cp "$f" "$cache/surfaces/gmsh/$name" ;;
    esac
  done < <(find "$cache/pkgs/gmsh-doc" -type f \( -name '*.stl' -o -name '*.stl.gz' \) -print0)
  touch "$cache/surfaces/gmsh.done"
fi

# Netgen: the .stl examples.
if [[ ! -f "$cache/surfaces/netgen.done" ]]; then
  rm -rf "$cache/surfaces/netgen"
  mkdir -p "$cache/surfaces/netgen"
  find "$cache/pkgs/netgen-doc" -type f -name '*.stl' -exec cp -t "$cache/surfaces/netgen" {} +
  touch "$cache/surfaces/netgen.done"
fi

# Manifest.
{
  printf 'source\tfile\tbytes\tlicence\n'
  for src in cgal gmsh netgen; do
    case "$src" in
      cgal) lic="CGAL data files (CC0 1.0 per CGAL's LICENSE; Debian package libcgal-demo)" ;;
      gmsh) lic="GPL-2+ with Gmsh exception (Debian package gmsh-doc)" ;;
      netgen) lic="LGPL-2.1 (Debian package netgen-doc)" ;;
    esac
    find "$cache/surfaces/$src" -maxdepth 1 -type f \( -name '*.off' -o -name '*.stl' \) \
      -printf "$src\t%f\t%s\t$lic\n" | LC_ALL=C sort
  done
} >"$cache/MANIFEST.tsv"

count=$(($(wc -l <"$cache/MANIFEST.tsv") - 1))
echo "$count surfaces in $cache/surfaces (manifest: $cache/MANIFEST.tsv)"

# All of them in one folder, as SOURCE_NAME links (scripts/benchmark.py --data reads one
# folder): cache/corpus/all.
rm -rf "$cache/all"
mkdir -p "$cache/all"
tail -n +2 "$cache/MANIFEST.tsv" | while IFS=$'\t' read -r src file _; do
  ln -s "../surfaces/$src/$file" "$cache/all/${src}_$file"
done

# Optional: diagnose every surface with the C++ input diagnosis.
if [[ -n "${TETMESHER_DIAGNOSE:-}" ]]; then
  files=$(find "$cache/surfaces" -type f \( -name '*.off' -o -name '*.stl' \) | LC_ALL=C sort |
    tr '\n' ':')
  TETMESHER_DIAGNOSE_FILES="$files" "$TETMESHER_DIAGNOSE" --gtest_filter='*CorpusFiles*' 2>&1 |
    grep -E "^$cache" | sed "s|^$cache/surfaces/||" >"$cache/diagnosis.txt" || true
  echo "$(grep -c ': ok$' "$cache/diagnosis.txt") of $count valid; see $cache/diagnosis.txt"
fi
