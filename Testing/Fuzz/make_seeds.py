"""Seed corpus of the FuzzSurface target (format: FuzzSurfaceInput.h).

Usage: python3 make_seeds.py OUT_DIR [SURFACE ...]

Each surface (.off, or .vtp/.vtk/.stl/.ply/.obj through vtkmodules when it is available) is
written in mode 2 (raw doubles) and mode 3 (float32), with flag variants; hand-made lattice
and grid seeds (tetrahedron, cube, two cubes sharing a face, open box) are added in modes 0
and 1. Surfaces that do not fit the decoder's bounds are skipped.
"""
import os
import struct
import sys

MAX_POINTS = 4000
MAX_TRIANGLES = 8000


def read_off(path):
    tokens = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                tokens.extend(line.split())
    assert tokens[0].endswith("OFF"), path
    tokens = tokens[1:]
    npts, nfaces = int(tokens[0]), int(tokens[1])
    pos = 3
    points = []
    for _ in range(npts):
        points.append(tuple(float(x) for x in tokens[pos:pos + 3]))
        pos += 3
    triangles = []
    for _ in range(nfaces):
        k = int(tokens[pos])
        ids = [int(x) for x in tokens[pos + 1:pos + 1 + k]]
        pos += 1 + k
        for i in range(1, k - 1):  # fan
            triangles.append((ids[0], ids[i], ids[i + 1]))
    return points, triangles


def read_vtk(path):
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter
    from vtkmodules.vtkIOGeometry import vtkOBJReader, vtkSTLReader
    from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    from vtkmodules.vtkIOPLY import vtkPLYReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    readers = {".vtp": vtkXMLPolyDataReader, ".vtk": vtkPolyDataReader, ".stl": vtkSTLReader,
               ".ply": vtkPLYReader, ".obj": vtkOBJReader}
    reader = readers[os.path.splitext(path)[1].lower()]()
    reader.SetFileName(path)
    triangulate = vtkTriangleFilter()
    triangulate.SetInputConnection(reader.GetOutputPort())
    triangulate.Update()
    poly = triangulate.GetOutput()
    points = [poly.GetPoint(i) for i in range(poly.GetNumberOfPoints())]
    triangles = []
    polys = poly.GetPolys()
    polys.InitTraversal()
    from vtkmodules.vtkCommonCore import vtkIdList
    ids = vtkIdList()
    while polys.GetNextCell(ids):
        triangles.append(tuple(ids.GetId(i) for i in range(3)))
    return points, triangles


def encode_real(points, triangles, mode, flags=0):
    out = bytearray([(mode & 3) | (flags << 2)])
    out += struct.pack("<H", len(points))
    fmt = "<3d" if mode == 2 else "<3f"
    for p in points:
        if mode != 2:  # float32: clamp what it cannot hold (huge-coordinate.off's 7.8e143)
            p = [max(-3.4e38, min(3.4e38, x)) for x in p]
        out += struct.pack(fmt, *p)
    for t in triangles:
        out += struct.pack("<3H", *t)
    return bytes(out)


def encode_lattice(points, triangles, mode, flags=0):
    """mode 0: coordinates as int16/256; mode 1: int8 grid coordinates in -4..4."""
    out = bytearray([(mode & 3) | (flags << 2), len(points) - 1])
    for p in points:
        for x in p:
            if mode == 0:
                out += struct.pack("<h", int(round(x * 256)))
            else:
                out += struct.pack("<b", int(x))
    for t in triangles:
        out += bytes(t)
    return bytes(out)


CUBE_POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
               (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_TRIANGLES = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
                  (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
TET_POINTS = [(0, 0, 0), (2, 0, 0), (0, 2, 0), (0, 0, 2)]
TET_TRIANGLES = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]


def two_cubes():
    """Two unit cubes sharing the face x = 1 (a valid two-region surface)."""
    points = CUBE_POINTS + [(2, 0, 0), (2, 1, 0), (2, 1, 1), (2, 0, 1)]
    shift = {0: 1, 1: 8, 2: 9, 3: 2, 4: 5, 5: 11, 6: 10, 7: 6}  # cube moved by +1 in x
    left = list(CUBE_TRIANGLES)  # its x = 1 face is the shared one
    right = [tuple(shift[i] for i in t) for t in CUBE_TRIANGLES
             if t not in [(3, 0, 4), (3, 4, 7)]]
    return points, left + right


def main():
    out_dir = sys.argv[1]
    os.makedirs(out_dir, exist_ok=True)
    count = 0

    def write(name, data):
        nonlocal count
        with open(os.path.join(out_dir, name), "wb") as f:
            f.write(data)
        count += 1

    hand = {"tet": (TET_POINTS, TET_TRIANGLES), "cube": (CUBE_POINTS, CUBE_TRIANGLES),
            "two-cubes": two_cubes(), "open-box": (CUBE_POINTS, CUBE_TRIANGLES[2:])}
    for name, (points, triangles) in hand.items():
        for mode in (0, 1):
            for flags in (0, 3):
                write("%s-m%d-f%d" % (name, mode, flags),
                      encode_lattice(points, triangles, mode, flags))
        write("%s-m2" % name, encode_real(points, triangles, 2))
        # flag 8: also the whole pipeline (size field, interior points, optimisation)
        write("%s-m0-f8" % name, encode_lattice(points, triangles, 0, 8))
    for path in sys.argv[2:]:
        try:
            if path.lower().endswith(".off"):
                points, triangles = read_off(path)
            else:
                points, triangles = read_vtk(path)
        except Exception as error:  # noqa: BLE001 (a seed is optional)
            print("make_seeds: skipped %s: %s" % (path, error))
            continue
        if len(points) > MAX_POINTS or len(triangles) > MAX_TRIANGLES or len(points) > 65535:
            print("make_seeds: skipped %s (too large)" % path)
            continue
        base = os.path.splitext(os.path.basename(path))[0]
        write(base + "-m2", encode_real(points, triangles, 2))
        write(base + "-m2-f3", encode_real(points, triangles, 2, 3))
        write(base + "-m3", encode_real(points, triangles, 3))
        if len(triangles) <= 1000:
            write(base + "-m3-f8", encode_real(points, triangles, 3, 8))
    print("make_seeds: %d seeds in %s" % (count, out_dir))


if __name__ == "__main__":
    main()
