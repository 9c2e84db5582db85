"""Writes the small defective surfaces of Testing/Data/defects (one defect each, plus one
valid control), read by Testing/Integration/TestDefects.py. Run from anywhere:

    /usr/bin/python3 Testing/Data/defects/make_defects.py

The .off files are plain text; nan-coordinate.vtp needs vtkmodules (an OFF reader cannot
read "nan").
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))

CUBE_POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
               (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
# Outward-oriented: bottom, top, y=0, x=1, y=1, x=0.
CUBE_TRIANGLES = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
                  (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def shifted(offset, dx, dy, dz):
    points = [(x + dx, y + dy, z + dz) for x, y, z in CUBE_POINTS]
    triangles = [tuple(i + offset for i in t) for t in CUBE_TRIANGLES]
    return points, triangles


def write_off(name, points, faces, comment):
    with open(os.path.join(HERE, name), "w") as f:
        f.write("OFF\n# %s\n%d %d 0\n" % (comment, len(points), len(faces)))
        for p in points:
            f.write("%s %s %s\n" % tuple(str(int(x)) if x == int(x) and abs(x) < 1e15 else repr(float(x)) for x in p))
        for t in faces:
            f.write("%d %s\n" % (len(t), " ".join(str(i) for i in t)))


def main():
    write_off("open-box.off", CUBE_POINTS, CUBE_TRIANGLES[:2] + CUBE_TRIANGLES[4:],
              "unit cube without its top (z = 1) face: 4 open edges")

    # Cube [0,1]^3 and cube [1,2]x[1,2]x[0,1]: they touch along the edge x = y = 1 only.
    second, tris = shifted(8, 1, 1, 0)
    # The second cube's points (1,1,0) and (1,1,1) are the first cube's 2 and 6.
    remap = {8 + 0: 2, 8 + 4: 6}
    points = CUBE_POINTS + [p for i, p in enumerate(second) if 8 + i not in remap]
    index = {}
    k = 8
    for i in range(8):
        if 8 + i in remap:
            index[8 + i] = remap[8 + i]
        else:
            index[8 + i] = k
            k += 1
    write_off("cubes-sharing-edge.off", points,
              CUBE_TRIANGLES + [tuple(index[i] for i in t) for t in tris],
              "two unit cubes that touch along one edge (points 2-6) only")

    # Two cubes sharing the face x = 1: the valid two-region surface (the shared face once).
    second, tris = shifted(8, 1, 0, 0)
    share = {8 + 0: 1, 8 + 3: 2, 8 + 4: 5, 8 + 7: 6}  # its x = 0 face is the first's x = 1
    points = CUBE_POINTS + [p for i, p in enumerate(second) if 8 + i not in share]
    index, k = {}, 8
    for i in range(8):
        if 8 + i in share:
            index[8 + i] = share[8 + i]
        else:
            index[8 + i] = k
            k += 1
    right = [tuple(index[i] for i in t) for t in tris[:10]]  # without its x = 0 face
    write_off("cubes-sharing-face.off", points, CUBE_TRIANGLES + right,
              "VALID: two unit cubes sharing the face x = 1 (two regions)")

    second, tris = shifted(8, 0.5, 0.5, 0.5)
    write_off("intersecting-cubes.off", CUBE_POINTS + second, CUBE_TRIANGLES + tris,
              "two unit cubes, the second moved by (0.5, 0.5, 0.5): they cross")

    flipped = list(CUBE_TRIANGLES)
    a, b, c = flipped[5]
    flipped[5] = (a, c, b)
    write_off("flipped-triangle.off", CUBE_POINTS, flipped,
              "unit cube with triangle 5 reversed")

    write_off("duplicate-triangles.off", CUBE_POINTS, CUBE_TRIANGLES + [CUBE_TRIANGLES[3]],
              "unit cube with triangle 3 given twice (as triangles 3 and 12)")

    # Tetrahedron a b c d; the edge a-b is split at its midpoint m on the face a-b-c only,
    # and the zero-area triangle a-m-b closes the surface.
    write_off("zero-area-triangle.off",
              [(0, 0, 0), (2, 0, 0), (0, 2, 0), (0, 0, 2), (1, 0, 0)],
              [(0, 2, 4), (4, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2), (0, 4, 1)],
              "tetrahedron whose edge 0-1 is split at 4 on one side: triangle 5 has zero area")

    # Finite, but beyond what the exact predicates can decide (they would overflow): a
    # fuzzer's find, which before the range check gave inverted tets and a crash.
    write_off("huge-coordinate.off",
              [p if i != 6 else (1, 1, 7.8e143) for i, p in enumerate(CUBE_POINTS)],
              CUBE_TRIANGLES, "unit cube whose point 6 is pulled out to z = 7.8e143")

    # Exact, but out of all proportion: one corner 1e36 away from a unit cube (a fuzzer's
    # sphere like this defeated edge recovery after seconds; TetGen aborts on it).
    write_off("outlying-point.off",
              [p if i != 6 else (1, 1, 1e36) for i, p in enumerate(CUBE_POINTS)],
              CUBE_TRIANGLES, "unit cube whose point 6 is pulled out to z = 1e36")

    # A quad with a hole cannot be an OFF face; the closest: the top of a box as one
    # non-convex polygon that goes around a hole and back along a slit (a keyhole).
    write_off("keyhole-polygon.off",
              CUBE_POINTS + [(0.25, 0.25, 1), (0.75, 0.25, 1), (0.75, 0.75, 1), (0.25, 0.75, 1)],
              CUBE_TRIANGLES[:2] + CUBE_TRIANGLES[4:] + [(4, 5, 6, 7, 4, 8, 11, 10, 9, 8)],
              "box whose top is one polygon around a square hole, joined by a slit 4-8")

    try:
        from vtkmodules.vtkCommonCore import vtkPoints
        from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
        from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    except ImportError:
        print("make_defects: no vtkmodules, nan-coordinate.vtp not written")
        return
    points = vtkPoints()
    points.SetDataTypeToDouble()
    for i, p in enumerate(CUBE_POINTS):
        points.InsertNextPoint(float("nan") if i == 6 else p[0], p[1], p[2])
    cells = vtkCellArray()
    for t in CUBE_TRIANGLES:
        cells.InsertNextCell(3, t)
    poly = vtkPolyData()
    poly.SetPoints(points)
    poly.SetPolys(cells)
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(os.path.join(HERE, "nan-coordinate.vtp"))
    writer.SetInputData(poly)
    writer.SetDataModeToAscii()
    writer.Write()


if __name__ == "__main__":
    main()
