#!/usr/bin/env python3
"""Writes the small tetrahedral meshes the tests and the demo read (run with /usr/bin/python3).

jittered-cube: the unit cube as a 4x4x4 grid of cells, 6 Kuhn tetrahedra per cell, interior
points moved by a fixed pseudo-random jitter so that the qualities vary. The same mesh is
written as .vtu, TetGen .node/.ele and Gmsh .msh (2.2 and 4.1), so a test can check that
every reader gives the same quality summary. Plus files with known defects.
"""
import math
import os
import random
import sys

from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE, vtkUnstructuredGrid
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

HERE = os.path.dirname(os.path.abspath(__file__))
N = 4


def grid_points():
    rng = random.Random(20261125)
    pts = []
    for k in range(N + 1):
        for j in range(N + 1):
            for i in range(N + 1):
                p = [i / N, j / N, k / N]
                interior = 0 < i < N and 0 < j < N and 0 < k < N
                if interior:
                    p = [c + rng.uniform(-0.3, 0.3) / N for c in p]
                pts.append(p)
    return pts


def volume(a, b, c, d):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6


def kuhn_tets(pts):
    def pid(i, j, k):
        return i + (N + 1) * (j + (N + 1) * k)
    tets = []
    # The 6 paths from corner 000 to 111 of a cell, one tet each.
    perms = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    for k in range(N):
        for j in range(N):
            for i in range(N):
                for perm in perms:
                    c = [0, 0, 0]
                    ids = [pid(i, j, k)]
                    for axis in perm:
                        c[axis] = 1
                        ids.append(pid(i + c[0], j + c[1], k + c[2]))
                    if volume(*[pts[v] for v in ids]) < 0:
                        ids[0], ids[1] = ids[1], ids[0]
                    tets.append(ids)
    return tets


def write_vtu(path, pts, cells, cell_type=VTK_TETRA):
    grid = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetDataTypeToDouble()
    for p in pts:
        points.InsertNextPoint(p)
    grid.SetPoints(points)
    for c in cells:
        grid.InsertNextCell(cell_type, len(c), c)
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(grid)
    writer.SetDataModeToAscii()
    writer.Write()


def write_tetgen(stem, pts, tets):
    with open(stem + ".node", "w") as f:
        f.write(f"{len(pts)} 3 0 0\n")
        for i, p in enumerate(pts):
            f.write(f"{i + 1} {p[0]!r} {p[1]!r} {p[2]!r}\n")
    with open(stem + ".ele", "w") as f:
        f.write(f"{len(tets)} 4 0\n")
        for i, t in enumerate(tets):
            f.write(f"{i + 1} " + " ".join(str(v + 1) for v in t) + "\n")


def write_msh2(path, pts, tets):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n")
        f.write(f"{len(pts)}\n")
        for i, p in enumerate(pts):
            f.write(f"{i + 1} {p[0]!r} {p[1]!r} {p[2]!r}\n")
        f.write("$EndNodes\n$Elements\n")
        f.write(f"{len(tets) + 1}\n")
        f.write("1 15 2 0 1 1\n")  # a point element, to be skipped
        for i, t in enumerate(tets):
            f.write(f"{i + 2} 4 2 0 1 " + " ".join(str(v + 1) for v in t) + "\n")
        f.write("$EndElements\n")


def write_msh41(path, pts, tets):
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n")
        f.write(f"1 {len(pts)} 1 {len(pts)}\n3 1 0 {len(pts)}\n")
        for i in range(len(pts)):
            f.write(f"{i + 1}\n")
        for p in pts:
            f.write(f"{p[0]!r} {p[1]!r} {p[2]!r}\n")
        f.write("$EndNodes\n$Elements\n")
        f.write(f"1 {len(tets)} 1 {len(tets)}\n3 1 4 {len(tets)}\n")
        for i, t in enumerate(tets):
            f.write(f"{i + 1} " + " ".join(str(v + 1) for v in t) + "\n")
        f.write("$EndElements\n")


def main(out):
    HERE = out  # noqa: N806 (the writers below take paths under the output folder)
    pts = grid_points()
    tets = kuhn_tets(pts)
    write_vtu(os.path.join(HERE, "jittered-cube.vtu"), pts, tets)
    write_tetgen(os.path.join(HERE, "jittered-cube"), pts, tets)
    write_msh2(os.path.join(HERE, "jittered-cube-v2.msh"), pts, tets)
    write_msh41(os.path.join(HERE, "jittered-cube-v41.msh"), pts, tets)
    # Defects.
    nan_pts = [list(p) for p in pts]
    nan_pts[7][1] = math.nan
    write_vtu(os.path.join(HERE, "bad-nan-coordinate.vtu"), nan_pts, tets)
    write_vtu(os.path.join(HERE, "bad-no-tetrahedra.vtu"), pts[:3], [[0, 1, 2]], VTK_TRIANGLE)
    with open(os.path.join(HERE, "bad-garbage.vtu"), "w") as f:
        f.write("this is not a VTK file\n")
    with open(os.path.join(HERE, "bad-truncated.msh"), "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0\n")
    with open(os.path.join(HERE, "bad-index.node"), "w") as f:
        f.write("4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n")
    with open(os.path.join(HERE, "bad-index.ele"), "w") as f:
        f.write("1 4 0\n0 0 1 2 9\n")


if __name__ == "__main__":
    # --check: regenerate into a scratch folder and fail if the committed files differ.
    if "--check" in sys.argv:
        import filecmp
        import tempfile
        with tempfile.TemporaryDirectory() as scratch:
            main(scratch)
            names = sorted(os.listdir(scratch))
            _, mismatch, errors = filecmp.cmpfiles(HERE, scratch, names, shallow=False)
            if mismatch or errors:
                sys.exit(f"Testing/Data differs from make_test_meshes.py output: {mismatch + errors}")
    else:
        main(HERE)
