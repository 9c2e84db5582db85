"""The `tetmesher` command line on good and bad files (run with /usr/bin/python3).

Usage: TestCommandLine.py TETMESHER_EXE DATA_DIR
Checks exit codes and messages: every format of the same mesh gives the same summary; each
defect is named with the file and where it is.
"""
import os
import shutil
import subprocess
import sys
import tempfile

exe, data = sys.argv[1], sys.argv[2]
failures = []


def run(*args):
    result = subprocess.run([exe, *args], capture_output=True, text=True, timeout=120)
    return result.returncode, result.stdout, result.stderr


def expect(args, code, out_has=(), err_has=()):
    rc, out, err = run(*args)
    problems = []
    if rc != code:
        problems.append(f"exit {rc}, expected {code}")
    problems += [f"stdout lacks {s!r}" for s in out_has if s not in out]
    problems += [f"stderr lacks {s!r}" for s in err_has if s not in err]
    if "ERR|" in err or "vtkExecutive" in err:
        problems.append("raw VTK error output leaked to stderr")
    if problems:
        failures.append(f"tetmesher {' '.join(args)}: {'; '.join(problems)}\n--- stdout\n{out}--- stderr\n{err}")
    return out


def d(name):
    return os.path.join(data, name)


# Usage.
expect(["--help"], 0, out_has=["quality MESH", "mesh SURFACE"])
expect(["mesh", "--help"], 0, out_has=["--size H", "--background FILE", "--time-limit", "--memory-limit"])
expect([], 2)
expect(["frobnicate"], 2, err_has=["unknown command 'frobnicate'"])
expect(["quality", "--help"], 0, out_has=["--size-array"])
expect(["quality"], 2)
expect(["quality", d("jittered-cube.vtu"), "--bogus"], 2, err_has=["unknown option '--bogus'"])

# The same mesh in four formats: identical summaries (after the file name).
summaries = []
for name in ["jittered-cube.vtu", "jittered-cube.node", "jittered-cube.ele",
             "jittered-cube-v2.msh", "jittered-cube-v41.msh"]:
    out = expect(["quality", d(name)], 0, out_has=["384 tetrahedra, 125 points", "quality Q", "dihedral"])
    summaries.append(out.split(":", 1)[-1])
if len(set(summaries)) != 1:
    failures.append("the formats disagree:\n" + "\n".join(summaries))

out = expect(["quality", d("jittered-cube.vtu"), "--histogram"], 0, out_has=["histogram of Q"])
bars = [line for line in out.splitlines() if line.strip()[:1].isdigit() and "-" in line.split()[0]]
if len(bars) != 20 or sum(int(line.split()[1]) for line in bars) != 384:
    failures.append("histogram rows do not add up to 384 tets:\n" + out)

# A legacy .vtk copy, written by VTK, reads the same.
with tempfile.TemporaryDirectory() as tmp:
    from vtkmodules.vtkIOLegacy import vtkUnstructuredGridWriter
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(d("jittered-cube.vtu"))
    writer = vtkUnstructuredGridWriter()
    writer.SetInputConnection(reader.GetOutputPort())
    legacy = os.path.join(tmp, "cube.vtk")
    writer.SetFileName(legacy)
    writer.Write()
    out = expect(["quality", legacy], 0)
    if out.split(":", 1)[-1] != summaries[0]:
        failures.append("legacy .vtk summary differs")
    # Size-scaled Q with a constant size array equals the plain Q.
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    grid = reader.GetOutput()
    h = vtkDoubleArray()
    h.SetName("h")
    h.SetNumberOfTuples(grid.GetNumberOfPoints())
    h.Fill(0.25)
    grid.GetPointData().AddArray(h)
    writer.SetInputData(grid)
    writer.SetFileName(os.path.join(tmp, "sized.vtk"))
    writer.Write()
    out = expect(["quality", os.path.join(tmp, "sized.vtk"), "--size-array", "h"], 0)
    if out.split(":", 1)[-1] != summaries[0]:
        failures.append("size-scaled Q with constant h differs from Q:\n" + out)
    expect(["quality", os.path.join(tmp, "sized.vtk"), "--size-array", "nope"], 1,
           err_has=["'nope'"])

# Bad input: exit 1, the message names the file and the defect.
expect(["quality", d("does-not-exist.vtu")], 1, err_has=["does-not-exist.vtu: no such file"])
expect(["quality", data], 1, err_has=["not a regular file"])
expect(["quality", d("bad-garbage.vtu")], 1, err_has=["bad-garbage.vtu: unreadable"])
expect(["quality", d("bad-nan-coordinate.vtu")], 1,
       err_has=["bad-nan-coordinate.vtu", "point 7 has a non-finite coordinate"])
expect(["quality", d("bad-no-tetrahedra.vtu")], 1, err_has=["no tetrahedra"])
expect(["quality", d("bad-truncated.msh")], 1, err_has=["bad-truncated.msh: line 7"])
expect(["quality", d("bad-index.ele")], 1, err_has=["bad-index.ele: line 2: vertex index out of range"])
expect(["quality", d("make_test_meshes.py")], 1, err_has=["unknown file type '.py'"])

# tetmesher mesh: good surfaces, options, limits.
corpus = os.path.join(data, "..", "..", "Data")
with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "sphere.vtu")
    line = expect(["mesh", os.path.join(corpus, "sphere.off"), "-o", out, "-q"], 0,
                  out_has=["tetrahedra", "1 region", "Q min"])
    expect(["quality", out], 0, out_has=["tetrahedra"])
    expect(["mesh", os.path.join(corpus, "sphere.off"), "-o", out, "-q", "--boundary-only"], 0,
           out_has=["(0 interior, 0 Steiner)"])
    stats = expect(["mesh", os.path.join(corpus, "cube.vtp"), "-o", out, "-q", "--size", "0.2", "--stats"], 0,
                   out_has=["histogram of Q"])
    # The quality the surface allows (SurfaceQualityBound.h) is said only when a triangle caps it
    # below 0.3: anchor.off's triangle 891 (2 sqrt(6) area / longest edge^2 = 0.000709, numpy).
    if "bound " in stats:
        failures.append("cube.vtp --stats names a quality bound:\n" + stats)
    for extra in ([], ["--with-vtk"]):
        expect(["mesh", os.path.join(corpus, "anchor.off"), "-o", out, "-q", "--boundary-only", "--stats"] + extra,
               0, out_has=["bound       Q min <= 0.000709 for every mesh that keeps the surface "
                           "(the shape of input cell 891)"])
    # `quality` says it too, from the mesh's field data.
    expect(["quality", out], 0, out_has=["bound       Q min <= 0.000709"])
    # .stl goes through the reader module loaded on demand (libtetmesherSurfaceReaders.so).
    expect(["mesh", os.path.join(corpus, "sphere.stl"), "-o", out, "-q", "--boundary-only"], 0,
           out_has=["(0 interior, 0 Steiner)"])
    # --timings lists every stage; --compress writes a smaller file of the same mesh.
    expect(["mesh", os.path.join(corpus, "sphere.off"), "-o", out, "-q", "--timings"], 0,
           out_has=["timings (wall seconds per stage)", "reading", "boundary recovery",
                    "lattice insertion", "edge splitting", "optimisation", "writing",
                    "total after main", "CPU time of all threads"])
    size_raw = os.path.getsize(out)
    expect(["mesh", os.path.join(corpus, "sphere.off"), "-o", out, "-q", "--compress"], 0)
    if not os.path.getsize(out) < size_raw:
        failures.append(f"--compress: {os.path.getsize(out)} bytes, not fewer than {size_raw}")
    # With recovery Steiner points, the time of their removal too (a part of the recovery's).
    expect(["mesh", os.path.join(corpus, "anchor.off"), "-o", out, "-q", "--boundary-only",
            "--timings"], 0,
           out_has=["boundary recovery\n", "(Steiner point removal, within the above)\n"])
    expect(["mesh", os.path.join(corpus, "nested_spheres.vtp"), "-o", out, "-q", "--holes"], 0,
           out_has=["1 region"])
    expect(["mesh", os.path.join(corpus, "turbine.off"), "-o", out, "-q", "--time-limit", "0.05"], 1,
           err_has=["exceeded the time limit of 0.05 s"])
    # A size field too fine for the memory is refused before any point is inserted: the cube
    # at h = 0.02 is estimated at 1.77e5 points, 354 MB; no output file is written.
    expect(["mesh", os.path.join(corpus, "cube.vtp"), "-o", out + ".mem.vtu", "-q", "--size", "0.02",
            "--memory-limit", "100"], 1,
           err_has=["about 1.77e+05 interior points", "354 MB of memory",
                    "more than the memory limit of 100 MB"])
    if os.path.exists(out + ".mem.vtu"):
        failures.append("--memory-limit: an output file was written after the refusal")
    # The boundary mesh alone is estimated too (2.5 kB per surface point): 386 points, 0.97 MB.
    expect(["mesh", os.path.join(corpus, "cube.vtp"), "-o", out, "-q", "--boundary-only",
            "--memory-limit", "0.5"], 1,
           err_has=["the surface has 386 points", "965 kB of memory, more than the memory limit of 500 kB"])
    # Beyond the 32-bit indices whatever the memory: h = 1e-5 in the unit cube.
    expect(["mesh", os.path.join(corpus, "cube.vtp"), "-o", out, "-q", "--size", "1e-5",
            "--memory-limit", "-1"], 1,
           err_has=["about 1.41e+15 interior points", "tetrahedra a mesh can have"])
    # --no-refine: the boundary mesh, then the optimisation (which may add points). On the tangled
    # tori the boundary mesh alone has tets flat in doubles (15 at 2026-12-02); these are gone,
    # every input triangle is still a boundary face, and the summary counts the added points.
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
    surface_reader = vtkXMLPolyDataReader()
    surface_reader.SetFileName(os.path.join(corpus, "tori_tangle.vtp"))
    surface_reader.Update()
    surface = surface_reader.GetOutput()
    triangles = {tuple(sorted(surface.GetCell(c).GetPointId(k) for k in range(3)))
                 for c in range(surface.GetNumberOfCells())}
    line = expect(["mesh", os.path.join(corpus, "tori_tangle.vtp"), "-o", out, "-q", "--no-refine"], 0,
                  out_has=[" 0 Steiner)"])
    grid_reader = vtkXMLUnstructuredGridReader()
    grid_reader.SetFileName(out)
    grid_reader.Update()
    grid = grid_reader.GetOutput()
    quality = grid.GetCellData().GetArray("Quality")
    flat = [c for c in range(grid.GetNumberOfCells()) if not quality.GetValue(c) > 0]
    faces = {}
    for c in range(grid.GetNumberOfCells()):
        ids = [grid.GetCell(c).GetPointId(k) for k in range(4)]
        for k in range(4):
            face = tuple(sorted(ids[:k] + ids[k + 1:]))
            faces[face] = faces.get(face, 0) + 1
    boundary = {face for face, count in faces.items() if count == 1}
    interior = int(line.split("points (")[1].split(" interior")[0]) if "points (" in line else -1
    if flat or boundary != triangles or \
            grid.GetNumberOfPoints() != surface.GetNumberOfPoints() + interior or interior <= 0:
        failures.append(f"--no-refine on tori_tangle.vtp: {len(flat)} tets of Q <= 0, boundary faces "
                        f"{'==' if boundary == triangles else '!='} input triangles, "
                        f"{grid.GetNumberOfPoints()} points for {surface.GetNumberOfPoints()} input "
                        f"and {interior} interior:\n{line}")
    # --point X,Y,Z (TetGen's -i list): anchor.off's boundary mesh has Steiner points; the given
    # points are output points 519 and 520, bit for bit, vertices of tets, and the summary counts
    # them as interior; points that cannot be vertices strictly inside are named.
    given = [(0.14, -0.044, -0.067), (0.344, 0.05, -0.036)]
    point_args = [a for p in given for a in ("--point", ",".join(repr(x) for x in p))]
    for extra in ([], ["--boundary-only"], ["--with-vtk"]):
        line = expect(["mesh", os.path.join(corpus, "anchor.off"), "-o", out, "-q"] + point_args + extra, 0,
                      out_has=["Steiner)"])
        grid_reader.SetFileName(out)
        grid_reader.Modified()
        grid_reader.Update()
        grid = grid_reader.GetOutput()
        ids = {grid.GetCell(c).GetPointId(k) for c in range(grid.GetNumberOfCells()) for k in range(4)}
        got = [grid.GetPoint(519 + i) for i in range(2)]
        if got != given or not {519, 520} <= ids or ("--boundary-only" in extra and "(2 interior" not in line):
            failures.append(f"--point {extra}: points 519, 520 are {got}, used {sorted({519, 520} & ids)}:\n{line}")
    # --points FILE: the same points from a TetGen .node file (numbered from 1, as TetGen's
    # NAME.a.node for -i), on both paths: the same points 519 and 520; a bad line is named.
    node = os.path.join(tmp, "anchor.a.node")
    with open(node, "w") as f:
        f.write("2 3 0 0\n" + "".join(f"{i + 1} {p[0]!r} {p[1]!r} {p[2]!r}\n" for i, p in enumerate(given)))
    for extra in ([], ["--with-vtk"]):
        expect(["mesh", os.path.join(corpus, "anchor.off"), "-o", out, "-q", "--points", node] + extra, 0)
        grid_reader.SetFileName(out)
        grid_reader.Modified()
        grid_reader.Update()
        got = [grid_reader.GetOutput().GetPoint(519 + i) for i in range(2)]
        if got != given:
            failures.append(f"--points {extra}: points 519, 520 are {got}")
    with open(node, "w") as f:
        f.write("2 3 0 0\n1 0.14 -0.044\n")
    expect(["mesh", os.path.join(corpus, "anchor.off"), "-o", out, "-q", "--points", node], 1,
           err_has=["anchor.a.node: line 2: expected point 1 of 2"])
    for point, message in (("2,0,0", "interior point 0 (2, 0, 0) is outside the meshed domain"),
                           ("-0.5,-0.1875,-0.103293", "coincides with input point"),
                           ("0.1,0.2", "--point wants a point X,Y,Z of three finite numbers, not '0.1,0.2'")):
        expect(["mesh", os.path.join(corpus, "anchor.off"), "-o", out, "-q", "--point", point],
               2 if "wants" in message else 1, err_has=[message])
    # Size options without interior points are said to do nothing.
    expect(["mesh", os.path.join(corpus, "cube.vtp"), "-o", out, "-q", "--no-refine", "--size", "0.1"], 0,
           err_has=["warning: --size has no effect with --no-refine (no interior points are placed)"])
    expect(["mesh", os.path.join(corpus, "cube.vtp"), "-o", out, "-q", "--boundary-only", "--gradation", "2"],
           0, err_has=["warning: --gradation has no effect with --boundary-only"])
    # Said once on the VTK path too (the static executable hands that path to its twin, which
    # parses the command line again).
    rc, _, err = run("mesh", os.path.join(corpus, "cube.vtp"), "-o", out, "-q", "--no-refine",
                     "--size", "0.1", "--with-vtk")
    if rc != 0 or err.count("warning: --size has no effect with --no-refine") != 1:
        failures.append(f"--with-vtk --no-refine --size: exit {rc}, the warning not once:\n{err}")
    expect(["mesh", os.path.join(corpus, "sphere.off"), "-o", out, "--memory-limit", "-2"], 2,
           err_has=["--memory-limit wants a number >= -1"])
    expect(["mesh", os.path.join(corpus, "sphere.off"), "-o", out, "--size", "-1"], 2,
           err_has=["--size wants a number"])
    expect(["mesh", os.path.join(corpus, "sphere.off")], 2, err_has=["no output file"])
    expect(["mesh", os.path.join(corpus, "sphere.off"), "-o", os.path.join(tmp, "x.stl")], 2,
           err_has=["unknown output type '.stl'"])
    expect(["mesh", os.path.join(corpus, "nosuch.stl"), "-o", out], 1, err_has=["no such file"])
    expect(["mesh", os.path.join(corpus, "sphere.off"), "-o", out, "--size-array", "nope"], 1,
           err_has=["'nope'"])

# Inner facets (--inner-facets, TetGen's dangling facets): a square sheet inside a cube (four
# open edges) is a defect without the option; with it, on both paths, the same mesh, in which
# each sheet triangle is a face of two tets of the one region and the cube's 12 triangles are
# the boundary.
with tempfile.TemporaryDirectory() as tmp:
    sheet = os.path.join(tmp, "sheet.off")
    with open(sheet, "w") as f:
        f.write("OFF\n12 14 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                "0.3 0.3 0.5\n0.7 0.3 0.5\n0.7 0.7 0.5\n0.3 0.7 0.5\n"
                "3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n"
                "3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n3 8 9 10\n3 8 10 11\n")
    expect(["mesh", sheet, "-o", os.path.join(tmp, "x.msh")], 1,
           err_has=["sheet.off", "4 open edges (points 8-9, 8-11, 9-10, 10-11; triangles 12, 13)",
                    "are kept with --inner-facets"])
    outputs = []
    for flags in ([], ["--with-vtk"]):
        msh = os.path.join(tmp, "sheet%d.msh" % len(flags))
        expect(["mesh", sheet, "-o", msh, "--inner-facets", "--size", "0.1", *flags], 0,
               out_has=["1 region"])
        with open(msh) as f:
            outputs.append(f.read())
    if outputs[0] != outputs[1]:
        failures.append("--inner-facets: the lean and VTK paths wrote different meshes")
    lines = outputs[0].split("\n")
    first = lines.index("$Elements") + 2
    elements = [l.split() for l in lines[first:first + int(lines[first - 1])]]
    faces = {}
    for e in elements:
        if e[1] == "4":
            ids = [int(v) for v in e[5:9]]
            for k in range(4):
                faces.setdefault(tuple(sorted(ids[:k] + ids[k + 1:])), []).append(e[4])
    tags = {tuple(sorted(int(v) for v in e[5:8])): int(e[4]) for e in elements if e[1] == "2"}
    one_sided = {f for f, regions in faces.items() if len(regions) == 1}
    sheet_faces = [f for f, cell in tags.items() if cell > 12]
    if len(tags) != 14 or one_sided != {f for f, cell in tags.items() if cell <= 12} or len(sheet_faces) != 2 \
            or any(len(faces.get(f, [])) != 2 or len(set(faces[f])) != 1 for f in sheet_faces):
        failures.append("--inner-facets: the sheet is not two inner faces, or the boundary is not the cube's:\n"
                        + repr((len(tags), len(one_sided), [faces.get(f) for f in sheet_faces])))

# The executable alone, away from its VTK part (the dynamic twin libexec/tetmesher-vtk of the
# static build, or libtetmesherVtk.so of the dynamic one): what needs VTK fails with a message
# that says so, and the lean path still meshes.
with tempfile.TemporaryDirectory() as tmp:
    alone = os.path.join(tmp, "bin", "tetmesher")
    os.makedirs(os.path.dirname(alone))
    shutil.copy2(exe, alone)
    result = subprocess.run([alone, "quality", d("jittered-cube.vtu")], capture_output=True,
                            text=True, timeout=120)
    if result.returncode != 1 or "its VTK part" not in result.stderr:
        failures.append(f"tetmesher without its VTK part: exit {result.returncode}, stderr:\n{result.stderr}")
    result = subprocess.run([alone, "mesh", os.path.join(corpus, "sphere.off"), "-o",
                             os.path.join(tmp, "sphere.vtu"), "-q", "--boundary-only"],
                            capture_output=True, text=True, timeout=120)
    if result.returncode != 0 or "tetrahedra" not in result.stdout:
        failures.append(f"tetmesher without its VTK part, lean path: exit {result.returncode}\n"
                        f"{result.stdout}{result.stderr}")

if failures:
    print("\n\n".join(failures))
    print(f"TestCommandLine: {len(failures)} failure(s)")
    sys.exit(1)
print("TestCommandLine: all checks passed")
