"""`tetmesher mesh -o OUT.msh | OUT.node | OUT.ele`: the mesh of the .vtu, exactly, in Gmsh's and
TetGen's formats (run with /usr/bin/python3).

Usage: TestExport.py TETMESHER_EXE CORPUS_DIR

For each surface the same command writes a .vtu (read back with VTK) and the exports, on the
lean path and with --with-vtk. Checked exactly: the nodes are the .vtu's points bit for bit (the
text reads back to the same double), the tets are its cells in order with the RegionId as tag
or attribute, the triangles are the faces on input triangles (InputFaceIds), each once, with
its input cell id + 1, oriented out of a tet that has it (exact rational arithmetic), and both
paths write the same bytes. Where Gmsh and TetGen are installed they read the files back: Gmsh
counts the nodes and elements, TetGen (`-rC`) finds the mesh consistent. Bad output names fail
with a message.
"""
import os
import shutil
import subprocess
import sys
import tempfile

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from mesh_invariants import orient_exact  # noqa: E402

exe, corpus = sys.argv[1], sys.argv[2]
failures = []
# The face opposite point i of a positive VTK tet, ordered so that its normal points out.
OUTWARD = [(1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1)]


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


def run(args):
    result = subprocess.run([exe, *args], capture_output=True, text=True, timeout=600)
    return result.returncode, result.stdout + result.stderr


def read_vtu(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    points = [tuple(float(x) for x in p) for p in vtk_to_numpy(grid.GetPoints().GetData())]
    cells = [tuple(int(grid.GetCell(c).GetPointId(i)) for i in range(4))
             for c in range(grid.GetNumberOfCells())]
    regions = [int(r) for r in vtk_to_numpy(grid.GetCellData().GetArray("RegionId"))]
    faces = vtk_to_numpy(grid.GetCellData().GetArray("InputFaceIds")).reshape(-1, 4)
    return points, cells, regions, [[int(x) for x in row] for row in faces]


def expected_triangles(cells, faces):
    """{sorted triple: (input cell, set of outward orientations from the tets that have it)}."""
    wanted = {}
    for t, row in enumerate(faces):
        for i, cell in enumerate(row):
            if cell < 0:
                continue
            tri = tuple(cells[t][k] for k in OUTWARD[i])
            entry = wanted.setdefault(tuple(sorted(tri)), (cell, set(), t))
            check(entry[0] == cell, "face %s has two input cells" % (tri,))
            entry[1].add(tri)
    return wanted


def same_cycle(a, b):
    return any(a == b[k:] + b[:k] for k in range(3))


def check_triangles(label, written, wanted, points, cells):
    """written: [(triple, input cell id)]. Each wanted triangle once, its id, outward."""
    keys = [tuple(sorted(tri)) for tri, _ in written]
    check(len(keys) == len(set(keys)), "%s: a triangle is written twice" % label)
    check(set(keys) == set(wanted), "%s: %d triangles written, %d faces on input triangles"
          % (label, len(set(keys)), len(wanted)))
    for tri, cell in written:
        entry = wanted.get(tuple(sorted(tri)))
        if entry is None:
            continue
        check(cell == entry[0], "%s: triangle %s has input cell %d, not %d" % (label, tri, cell, entry[0]))
        check(any(same_cycle(tri, o) for o in entry[1]),
              "%s: triangle %s is not oriented out of a tet that has it" % (label, tri))
        # And exactly: the tet's fourth point lies behind the triangle.
        tet = cells[entry[2]]
        apex = [p for p in tet if p not in tri][0]
        check(orient_exact(points[tri[0]], points[tri[1]], points[tri[2]], points[apex]) < 0,
              "%s: triangle %s faces into its tet" % (label, tri))


def read_msh(path):
    with open(path) as f:
        lines = f.read().split("\n")
    check(lines[0:3] == ["$MeshFormat", "2.2 0 8", "$EndMeshFormat"], "%s: header" % path)
    n = int(lines[4])
    nodes = []
    for k, line in enumerate(lines[5:5 + n]):
        fields = line.split()
        check(int(fields[0]) == k + 1, "%s: node numbering" % path)
        nodes.append(tuple(float(x) for x in fields[1:4]))
    at = 5 + n
    check(lines[at] == "$EndNodes" and lines[at + 1] == "$Elements", "%s: sections" % path)
    m = int(lines[at + 2])
    tets, triangles = [], []
    for k, line in enumerate(lines[at + 3:at + 3 + m]):
        f = [int(x) for x in line.split()]
        check(f[0] == k + 1 and f[2] == 2, "%s: element %d numbering or tags" % (path, k + 1))
        if f[1] == 4:
            tets.append((f[3], f[4], tuple(x - 1 for x in f[5:9])))
        elif check(f[1] == 2, "%s: element type %d" % (path, f[1])):
            check(f[3] == 1, "%s: triangle physical tag %d" % (path, f[3]))
            triangles.append((tuple(x - 1 for x in f[5:8]), f[4] - 1))
    check(lines[at + 3 + m] == "$EndElements", "%s: end" % path)
    return nodes, tets, triangles


def read_tetgen(name):
    def rows(ext):
        with open(name + ext) as f:
            lines = [l.split() for l in f if l.strip() and not l.startswith("#")]
        return lines[0], lines[1:]
    head, node_rows = rows(".node")
    check(head == [str(len(node_rows)), "3", "0", "0"], "%s.node: header %s" % (name, head))
    nodes = []
    for k, r in enumerate(node_rows):
        check(int(r[0]) == k, "%s.node: numbering" % name)
        nodes.append(tuple(float(x) for x in r[1:4]))
    head, ele_rows = rows(".ele")
    check(head == [str(len(ele_rows)), "4", "1"], "%s.ele: header %s" % (name, head))
    tets = [(int(r[5]), tuple(int(x) for x in r[1:5])) for r in ele_rows]
    head, face_rows = rows(".face")
    check(head == [str(len(face_rows)), "1"], "%s.face: header %s" % (name, head))
    triangles = [(tuple(int(x) for x in r[1:4]), int(r[4]) - 1) for r in face_rows]
    return nodes, tets, triangles


tmp = tempfile.mkdtemp(prefix="tetmesher-export-")
gmsh, tetgen = shutil.which("gmsh"), shutil.which("tetgen")
# Two regions (nested shells), and CAD parts with recovery Steiner points: the boundary mesh
# alone (flat tets included) and the full pipeline.
cases = [("nested_spheres.vtp", []), ("gear.vtp", ["--boundary-only"]), ("anchor.off", [])]
for surface, options in cases:
    src = os.path.join(corpus, surface)
    base = os.path.join(tmp, os.path.splitext(surface)[0])
    status, out = run(["mesh", src, "-o", base + ".vtu", "-q", *options])
    if not check(status == 0, "%s: .vtu: %s" % (surface, out)):
        continue
    points, cells, regions, faces = read_vtu(base + ".vtu")
    wanted = expected_triangles(cells, faces)
    for path, extra in [(base + ".msh", []), (base + "-vtk.msh", ["--with-vtk"]),
                        (base + ".node", []), (base + "-vtk.ele", ["--with-vtk"])]:
        status, out = run(["mesh", src, "-o", path, "-q", *options, *extra])
        check(status == 0, "%s -> %s: %s" % (surface, path, out))
    label = surface + " .msh"
    nodes, tets, triangles = read_msh(base + ".msh")
    check(nodes == points, "%s: nodes differ from the .vtu's points" % label)
    check([t[2] for t in tets] == cells, "%s: tets differ from the .vtu's cells" % label)
    check([t[0] - 1 for t in tets] == regions and [t[1] - 1 for t in tets] == regions,
          "%s: tet tags are not RegionId + 1" % label)
    check_triangles(label, triangles, wanted, points, cells)
    with open(base + ".msh", "rb") as a, open(base + "-vtk.msh", "rb") as b:
        check(a.read() == b.read(), "%s: the lean and VTK paths wrote different .msh" % surface)
    label = surface + " TetGen"
    nodes, tets, triangles = read_tetgen(base)
    check(nodes == points, "%s: nodes differ from the .vtu's points" % label)
    check([t[1] for t in tets] == cells, "%s: tets differ from the .vtu's cells" % label)
    check([t[0] for t in tets] == regions, "%s: attributes are not RegionId" % label)
    check_triangles(label, triangles, wanted, points, cells)
    for ext in (".node", ".ele", ".face"):
        with open(base + ext, "rb") as a, open(base + "-vtk" + ext, "rb") as b:
            check(a.read() == b.read(), "%s: the lean and VTK paths wrote different %s" % (surface, ext))
    if gmsh:
        result = subprocess.run([gmsh, "-check", base + ".msh"], capture_output=True, text=True,
                                timeout=300)
        log = result.stdout + result.stderr
        check(result.returncode == 0 and "Error" not in log
              and "%d nodes" % len(points) in log
              and "%d elements" % (len(cells) + len(wanted)) in log,
              "%s: gmsh -check: %s" % (surface, log[-600:]))
    if tetgen:
        work = os.path.join(tmp, "tetgen-" + os.path.splitext(surface)[0])
        os.mkdir(work)
        for ext in (".node", ".ele", ".face"):
            shutil.copy(base + ext, os.path.join(work, "m" + ext))
        result = subprocess.run([tetgen, "-rC", "m"], cwd=work, capture_output=True, text=True,
                                timeout=300)
        log = result.stdout + result.stderr
        check(result.returncode == 0 and "the mesh appears to be consistent" in log,
              "%s: tetgen -rC: %s" % (surface, log[-600:]))
    print("%s: %d tets, %d boundary triangles, .msh and TetGen files exact%s%s"
          % (surface, len(cells), len(wanted), ", read by Gmsh" if gmsh else "",
             ", consistent for TetGen" if tetgen else ""))

# Bad output names: an unknown type before any work, an unwritable place after it.
status, out = run(["mesh", os.path.join(corpus, "cube.vtp"), "-o", os.path.join(tmp, "x.xyz")])
check(status == 2 and "unknown output type '.xyz'" in out and ".msh" in out, "unknown type: %s" % out)
bad = os.path.join(tmp, "no-such-dir", "x.msh")
for extra in ([], ["--with-vtk"]):
    status, out = run(["mesh", os.path.join(corpus, "cube.vtp"), "-o", bad, "-q", *extra])
    check(status == 1 and bad in out and "could not be written" in out,
          "unwritable %s: %s" % (extra, out))

shutil.rmtree(tmp)
if failures:
    print("\n".join(failures[:40]))
    sys.exit(1)
print("TestExport: ok")
