"""Medit .mesh files in and out of `tetmesher` (run with /usr/bin/python3).

Usage: TestMedit.py TETMESHER_EXE CORPUS_DIR

In: each case's .off is written as a Medit .mesh the way other programs write them (comments,
keywords in mixed case, numbers broken across lines, vertex references, Edges and Corners
sections to skip, triangles and quadrilaterals in sections of their own). Meshing it must give
the mesh of the same surface as .off byte for byte (written as .msh, which holds no timing), on
the lean path and with --with-vtk. Out: `-o OUT.mesh` holds exactly the points, tetrahedra,
regions and boundary triangles of `-o OUT.msh` (Gmsh's export, checked by CLI.Export); Gmsh and
TetGen read it back; `tetmesher quality` reads it as it reads the .msh. Defective files fail
with a message naming the file and the defect, the same on both paths.
"""
import os
import shutil
import subprocess
import sys
import tempfile

from off_text import read_off

exe, corpus = sys.argv[1], sys.argv[2]
failures = []
CASES = ["sphere.off", "cubes.off", "hole.off", "anchor.off"]


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


def run(args, cwd=None):
    result = subprocess.run([exe, *args], capture_output=True, text=True, timeout=600, cwd=cwd)
    return result.returncode, result.stdout + result.stderr


def write(path, lines):
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def write_medit(path, points, triangles, quads):
    lines = ["# written by TestMedit.py", "MeshVersionFormatted 2", "", "Dimension", "3",
             "Vertices", str(len(points))]
    for i, x in enumerate(points):
        # x y on one line, z and the reference on the next
        lines += ["  %s %s" % (x[0], x[1]), "  %s %d" % (x[2], i % 3)]
    lines += ["Corners 2", "1 2", "edges", "1", "1 2 5"]
    if triangles:
        lines += ["TRIANGLES", str(len(triangles))]
        lines += ["%s 4" % " ".join(str(v + 1) for v in t) for t in triangles]
    if quads:
        lines += ["Quadrilaterals %d" % len(quads)]
        lines += ["%s %d" % (" ".join(str(v + 1) for v in q), -3) for q in quads]
    write(path, lines + ["End"])


def msh_sections(path):
    """(points as text tuples, tets [(elementary tag, ids)], triangles [(elementary tag, ids)])."""
    with open(path) as f:
        lines = f.read().split("\n")
    i = lines.index("$Nodes")
    points = [tuple(l.split()[1:4]) for l in lines[i + 2:i + 2 + int(lines[i + 1])]]
    j = lines.index("$Elements")
    tets, triangles = [], []
    for line in lines[j + 2:j + 2 + int(lines[j + 1])]:
        w = line.split()
        ids = tuple(int(v) - 1 for v in w[3 + int(w[2]):])
        (tets if w[1] == "4" else triangles).append((int(w[4]), ids))
    return points, tets, triangles


def medit_sections(path):
    with open(path) as f:
        words = f.read().split()
    check(words[:4] == ["MeshVersionFormatted", "2", "Dimension", "3"] and words[-1] == "End",
          "%s: header or end: %s ... %s" % (path, words[:4], words[-1:]))
    sections, k = {}, 4
    while k < len(words) - 1:
        name, n = words[k], int(words[k + 1])
        width = {"Vertices": 4, "Tetrahedra": 5, "Triangles": 4}[name]
        rows = [words[k + 2 + width * r:k + 2 + width * (r + 1)] for r in range(n)]
        sections[name] = rows
        k += 2 + width * n
    points = [tuple(r[:3]) for r in sections["Vertices"]]
    check(all(r[3] == "0" for r in sections["Vertices"]), "%s: vertex references not 0" % path)
    tets = [(int(r[4]), tuple(int(v) - 1 for v in r[:4])) for r in sections["Tetrahedra"]]
    triangles = [(int(r[3]), tuple(int(v) - 1 for v in r[:3]))
                 for r in sections.get("Triangles", [])]
    return points, tets, triangles


def mesh_bytes(path, out, extra):
    code, text = run(["mesh", path, "-o", out, *extra])
    if not check(code == 0, "%s %s: exit %d: %s" % (path, extra, code, text)):
        return None
    with open(out, "rb") as f:
        return f.read()


with tempfile.TemporaryDirectory() as tmp:
    # 1. In: the same mesh as the surface's .off.
    for case in CASES:
        points, polygons = read_off(os.path.join(corpus, case))
        triangles = [p for p in polygons if len(p) == 3]
        quads = [p for p in polygons if len(p) == 4]
        if not check(len(triangles) + len(quads) == len(polygons), "%s: polygons of 5+ corners" % case):
            continue
        stem = os.path.join(tmp, os.path.splitext(case)[0])
        # The .off with the polygons in the order of the .mesh's sections (input cell ids).
        write(stem + "-ordered.off", ["OFF", "%d %d 0" % (len(points), len(polygons))] +
              [" ".join(x) for x in points] +
              ["%d %s" % (len(p), " ".join(str(v) for v in p)) for p in triangles + quads])
        write_medit(stem + ".mesh", points, triangles, quads)
        for extra in (["--boundary-only"], []):
            reference = mesh_bytes(stem + "-ordered.off", stem + "-ref.msh", extra)
            for path_flag in ([], ["--with-vtk"]):
                got = mesh_bytes(stem + ".mesh", stem + "-got.msh", extra + path_flag)
                check(got is not None and got == reference,
                      "%s %s: the .mesh does not mesh as the .off" % (case, extra + path_flag))
        print("%s: %d triangles, %d quadrilaterals as .mesh: the .off's mesh" % (case, len(triangles), len(quads)))

    # 2. Out: the .msh export's mesh exactly, read back by Gmsh, TetGen and `quality`.
    gmsh, tetgen = shutil.which("gmsh"), shutil.which("tetgen")
    outputs = [("sphere.off", []), ("nested_spheres.vtp", []),
               ("nested_spheres.vtp", ["--region", "0,0,0.01,-7", "--region", "0,0,0.75,12"]),
               ("hole.off", ["--boundary-only"])]
    for surface, extra in outputs:
        label = "%s %s" % (surface, " ".join(extra))
        base = os.path.join(tmp, "out-" + os.path.splitext(surface)[0] + str(len(extra)))
        for ext in (".msh", ".mesh"):
            code, text = run(["mesh", os.path.join(corpus, surface), "-o", base + ext, *extra])
            check(code == 0, "%s -> %s: exit %d: %s" % (label, ext, code, text))
        code, text = run(["mesh", os.path.join(corpus, surface), "-o", base + "-vtk.mesh",
                          "--with-vtk", *extra])
        with open(base + ".mesh", "rb") as a, open(base + "-vtk.mesh", "rb") as b:
            check(code == 0 and a.read() == b.read(), "%s: the lean and VTK paths wrote different .mesh" % label)
        points, tets, triangles = msh_sections(base + ".msh")
        m_points, m_tets, m_triangles = medit_sections(base + ".mesh")
        check(m_points == points, "%s: .mesh vertices differ from the .msh nodes" % label)
        check([t[1] for t in m_tets] == [t[1] for t in tets], "%s: .mesh tetrahedra differ" % label)
        check(m_triangles == triangles, "%s: .mesh triangles or references differ" % label)
        regions = sorted(set(t[0] for t in m_tets))
        if "--region" in extra:
            check(regions == [-7, 12], "%s: references %s, not the region attributes" % (label, regions))
        else:
            check([t[0] for t in m_tets] == [t[0] for t in tets] and regions == list(range(1, len(regions) + 1)),
                  "%s: references are not RegionId + 1: %s" % (label, regions))
        if surface == "nested_spheres.vtp":
            check(len(regions) == 2, "%s: %d regions" % (label, len(regions)))
        q_msh = run(["quality", base + ".msh"])
        q_mesh = run(["quality", base + ".mesh"])
        check(q_mesh[0] == 0 and q_mesh[1].replace(".mesh", "") == q_msh[1].replace(".msh", ""),
              "%s: quality of the .mesh %r, of the .msh %r" % (label, q_mesh, q_msh))
        if gmsh:
            result = subprocess.run([gmsh, "-check", base + ".mesh"], capture_output=True,
                                    text=True, timeout=300)
            log = result.stdout + result.stderr
            check(result.returncode == 0 and "Error" not in log
                  and "%d nodes" % len(points) in log and "%d tetrahedra" % len(tets) in log
                  and "%d triangles" % len(triangles) in log,
                  "%s: gmsh -check: %s" % (label, log[-600:]))
        if tetgen:
            work = os.path.join(tmp, "tetgen" + os.path.basename(base))
            os.mkdir(work)
            shutil.copy(base + ".mesh", os.path.join(work, "m.mesh"))
            result = subprocess.run([tetgen, "-rC", "m.mesh"], cwd=work, capture_output=True,
                                    text=True, timeout=300)
            log = result.stdout + result.stderr
            check(result.returncode == 0 and "the mesh appears to be consistent" in log
                  and "Input tetrahedra: %d" % len(tets) in log,
                  "%s: tetgen -rC: %s" % (label, log[-600:]))
        print("%s: .mesh of %d tets, %d triangles = the .msh's%s%s"
              % (label, len(tets), len(triangles), ", read by Gmsh" if gmsh else "",
                 ", consistent for TetGen" if tetgen else ""))

    # 3. Defects: exit 1, the file and the defect named, the same on both paths.
    head = ["MeshVersionFormatted 1", "Dimension 3"]
    square = ["Vertices 4", "0 0 0 0", "1 0 0 0", "1 1 0 0", "0 1 0 0"]
    defects = {
        "2d.mesh": (["MeshVersionFormatted 1", "Dimension 2", "Vertices 0"],
                    "line 2: a 2D mesh: tetmesher meshes closed surfaces in 3D"),
        "index.mesh": (head + square + ["Triangles 2", "1 2 3 0", "1 3 5 0"],
                       "triangle 2 uses vertex 5, not among the 4 vertices"),
        "zero.mesh": (head + square + ["Quadrilaterals 1", "0 1 2 3 0"],
                      "quadrilateral 1 uses vertex 0, not among the 4 vertices"),
        "keyword.mesh": (head + square + ["Triangles 1 1 2 3 0", "Facets 1"],
                         "line 9: unknown keyword 'Facets'"),
        "short.mesh": (head + ["Vertices 2", "0 0 0 0", "1 1"],
                       "line 5: the file ends where the z of vertex 2 of 2 was expected"),
        "number.mesh": (head + ["Vertices 1", "0 0 zero 0"],
                        "line 4: expected the z of vertex 1 of 1, read 'zero'"),
        "curved.mesh": (head + square + ["TrianglesP2 0"],
                        "second-order (curved) triangles (TrianglesP2)"),
        "notmedit.mesh": (["OFF", "0 0 0"], "not a Medit .mesh file (it starts with 'OFF'"),
        "empty.mesh": (head + square + ["End"], "no Triangles or Quadrilaterals"),
        "count.mesh": (head + ["Corners 9223372036854775807", "1 2"],
                       "line 4: the file ends inside the corners section"),
        "toobig.mesh": (head + ["Corners 92233720368547758070"],
                        "line 3: expected the number of corners, read '92233720368547758070'"),
    }
    for name, (lines, message) in sorted(defects.items()):
        write(os.path.join(tmp, name), lines)
        outputs = []
        for path_flag in ([], ["--with-vtk"]):
            code, text = run(["mesh", name, "-o", "x.vtu", *path_flag], cwd=tmp)
            outputs.append(text)
            check(code == 1 and message in text and name in text,
                  "%s %s: exit %d: %s" % (name, path_flag, code, text))
        check(outputs[0] == outputs[1], "%s: the two paths say %r and %r" % (name, *outputs))
    code, text = run(["quality", "empty.mesh"], cwd=tmp)
    check(code == 1 and "empty.mesh" in text and "no tetrahedra" in text, "quality empty.mesh: %d %s" % (code, text))
    code, text = run(["mesh", os.path.join(corpus, "sphere.off"), "-o", os.path.join(tmp, "x.meshb")])
    check(code == 2 and "unknown output type '.meshb'" in text and ".mesh" in text, "x.meshb: %d %s" % (code, text))

for f in failures:
    print("FAIL:", f)
print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
