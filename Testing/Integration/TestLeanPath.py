"""The lean `tetmesher mesh` (no VTK loaded) gives what the VTK path gives (run with /usr/bin/python3).

Usage: TestLeanPath.py TETMESHER_EXE CORPUS_DIR TEST_DATA_DIR

For each case the same command runs twice: as it is (the lean path: the core, the own .off/.vtp/
.stl readers and .vtu writer) and with --with-vtk (vtkTetMesher, VTK's readers and writers). Both
.vtu files are read back with vtkXMLUnstructuredGridReader and compared exactly: points bit
for bit, cells, every point, cell and field array with its name, type, components and values
(MeshingSeconds only by name and type: it is a wall time). stdout must be the same but for the
seconds of the summary line; failures must give the same message and exit status. The dynamic
loader's log checks that the lean runs load no VTK library and the others do.
"""
import os
import re
import struct
import subprocess
import sys
import tempfile

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter, vtkXMLUnstructuredGridReader

exe, corpus, data = sys.argv[1], sys.argv[2], sys.argv[3]
failures = []


def run(args, lean):
    """Runs tetmesher; returns (status, stdout, stderr, VTK libraries loaded)."""
    env = dict(os.environ, LD_DEBUG="files", LD_DEBUG_OUTPUT=os.path.join(tmp, "ld"))
    for name in os.listdir(tmp):
        if name.startswith("ld."):
            os.remove(os.path.join(tmp, name))
    command = [exe, *args] if lean else [exe, *args, "--with-vtk"]
    result = subprocess.run(command, capture_output=True, text=True, timeout=600, env=env)
    loaded = False
    for name in os.listdir(tmp):
        if name.startswith("ld."):
            with open(os.path.join(tmp, name), errors="replace") as log:
                loaded = loaded or "libvtk" in log.read()
    return result.returncode, result.stdout, result.stderr, loaded


def raw(array):
    """The values of a numeric array as (dtype, bytes): equal bit for bit, NaN included."""
    values = vtk_to_numpy(array)
    return str(values.dtype), values.tobytes()


def arrays(attributes):
    out = {}
    for i in range(attributes.GetNumberOfArrays()):
        array = attributes.GetAbstractArray(i)
        values = raw(array) if array.IsNumeric() else \
            [array.GetValue(k) for k in range(array.GetNumberOfValues())]
        out[array.GetName()] = (array.GetClassName(), array.GetNumberOfComponents(), values, i)
    return out


def read(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def compare_meshes(case, lean_path, vtk_path):
    a, b = read(lean_path), read(vtk_path)
    problems = []
    if a.GetNumberOfPoints() != b.GetNumberOfPoints() or a.GetNumberOfCells() != b.GetNumberOfCells():
        problems.append(f"{a.GetNumberOfPoints()} points, {a.GetNumberOfCells()} cells vs "
                        f"{b.GetNumberOfPoints()}, {b.GetNumberOfCells()}")
    else:
        pa, pb = a.GetPoints().GetData(), b.GetPoints().GetData()
        if pa.GetClassName() != pb.GetClassName():
            problems.append(f"points stored as {pa.GetClassName()} vs {pb.GetClassName()}")
        if raw(pa) != raw(pb):
            problems.append("points differ")
        for name, get in [("connectivity", lambda g: g.GetCells().GetConnectivityArray()),
                          ("offsets", lambda g: g.GetCells().GetOffsetsArray()),
                          ("types", lambda g: g.GetCellTypesArray())]:
            if raw(get(a)) != raw(get(b)):
                problems.append(f"cell {name} differ")
    for where, get in [("point", lambda g: g.GetPointData()), ("cell", lambda g: g.GetCellData()),
                       ("field", lambda g: g.GetFieldData())]:
        xa, xb = arrays(get(a)), arrays(get(b))
        if list(xa) != list(xb):
            problems.append(f"{where} arrays {list(xa)} vs {list(xb)}")
            continue
        for name in xa:
            ca, na, va, ia = xa[name]
            cb, nb, vb, ib = xb[name]
            if (ca, na, ia) != (cb, nb, ib):
                problems.append(f"{where} array {name}: {ca} x{na} at {ia} vs {cb} x{nb} at {ib}")
            elif name != "MeshingSeconds" and va != vb:
                problems.append(f"{where} array {name}: values differ")
    if a.GetCellData().GetScalars() is None or a.GetCellData().GetScalars().GetName() != "Quality":
        problems.append("Quality is not the active cell scalars")
    if problems:
        failures.append(f"{case}: " + "; ".join(problems))


def without_seconds(text):
    return re.sub(r", [0-9.]+ s\n", ", S s\n", text)


def case(name, args, expect_lean=True):
    out_lean = os.path.join(tmp, "lean.vtu")
    out_vtk = os.path.join(tmp, "vtk.vtu")
    for path in (out_lean, out_vtk):
        if os.path.exists(path):
            os.remove(path)
    la = [a if a != "OUT" else out_lean for a in args]
    va = [a if a != "OUT" else out_vtk for a in args]
    rl, ol, el, loaded_lean = run(la, True)
    rv, ov, ev, loaded_vtk = run(va, False)
    if loaded_lean == expect_lean:
        failures.append(f"{name}: the run without --with-vtk {'loaded' if loaded_lean else 'did not load'} VTK")
    if not loaded_vtk:
        failures.append(f"{name}: --with-vtk did not load VTK")
    if rl != rv or el != ev:
        failures.append(f"{name}: exit {rl} vs {rv}; stderr\n{el!r}\nvs\n{ev!r}")
    if without_seconds(ol.replace(out_lean, "OUT")) != without_seconds(ov.replace(out_vtk, "OUT")):
        failures.append(f"{name}: stdout\n{ol}vs\n{ov}")
    if rl == 0 and rv == 0:
        compare_meshes(name, out_lean, out_vtk)
    print(f"{name}: {'lean' if not loaded_lean else 'VTK'} path, exit {rl}", flush=True)


def d(name):
    return os.path.join(corpus, name)


def write_binary_stl(path, facets, header=b"binary STL written by TestLeanPath", count=None, tail=b""):
    """facets: triples of (x, y, z) corners; count: the facet count stored in the header."""
    with open(path, "wb") as f:
        f.write(header.ljust(80, b"\0"))
        f.write(struct.pack("<I", len(facets) if count is None else count))
        for facet in facets:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for corner in facet:
                f.write(struct.pack("<3f", *corner))
            f.write(b"\0\0")
        f.write(tail)


def cube_facets(zero):
    """The 12 outward triangles of the unit cube; `zero` is the value written for 0."""
    corners = [(x, y, z) for z in (zero, 1.0) for y in (zero, 1.0) for x in (zero, 1.0)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    out = []
    for a, b, c, e in quads:
        out += [(corners[a], corners[b], corners[c]), (corners[a], corners[c], corners[e])]
    return out


with tempfile.TemporaryDirectory() as tmp:
    # A surface with a point array of sizes, in a .vtp written by VTK (appended raw).
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(d("torus.vtp"))
    reader.Update()
    torus = reader.GetOutput()
    sizes = vtkFloatArray()
    sizes.SetName("h")
    for p in range(torus.GetNumberOfPoints()):
        x, y, z = torus.GetPoint(p)
        sizes.InsertNextValue(0.08 + 0.06 * (x + 1.35) / 2.7)
    torus.GetPointData().AddArray(sizes)
    sized = os.path.join(tmp, "torus-sized.vtp")
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(torus)
    writer.SetDataModeToAppended()
    writer.SetEncodeAppendedData(False)
    writer.SetCompressorTypeToNone()
    writer.SetFileName(sized)
    writer.Write()

    case("star.off boundary only", ["mesh", d("star.off"), "-o", "OUT", "-q", "--boundary-only"])
    case("star.off", ["mesh", d("star.off"), "-o", "OUT", "-q", "--stats"])
    case("sphere.off", ["mesh", d("sphere.off"), "-o", "OUT", "-q"])
    case("fandisk.off boundary only", ["mesh", d("fandisk.off"), "-o", "OUT", "-q", "--boundary-only"])
    case("cube.vtp --size 0.2 --stats", ["mesh", d("cube.vtp"), "-o", "OUT", "-q", "--size", "0.2", "--stats"])
    case("cube.vtp --compress", ["mesh", d("cube.vtp"), "-o", "OUT", "-q", "--compress"])
    case("nested_spheres.vtp (2 regions)", ["mesh", d("nested_spheres.vtp"), "-o", "OUT", "-q"])
    case("nested_spheres.vtp --holes", ["mesh", d("nested_spheres.vtp"), "-o", "OUT", "-q", "--holes"])
    case("tori_tangle.vtp boundary only", ["mesh", d("tori_tangle.vtp"), "-o", "OUT", "-q", "--boundary-only"])
    case("alternator.vtp boundary only", ["mesh", d("alternator.vtp"), "-o", "OUT", "-q", "--boundary-only"])
    case("tori_tangle.vtp --no-refine", ["mesh", d("tori_tangle.vtp"), "-o", "OUT", "-q", "--no-refine"])
    case("anchor.off --point (after the input points, before the Steiner points)",
         ["mesh", d("anchor.off"), "-o", "OUT", "-q", "--point", "0.14,-0.044,-0.067", "--point", "0.344,0.05,-0.036"])
    case("cube.vtp --point outside", ["mesh", d("cube.vtp"), "-o", "OUT", "-q", "--point", "2,0.5,0.5"])
    case("torus.vtp --no-optimize --gradation 1.3", ["mesh", d("torus.vtp"), "-o", "OUT", "-q",
                                                     "--no-optimize", "--gradation", "1.3"])
    case("torus with a size array", ["mesh", sized, "-o", "OUT", "-q", "--size-array", "h",
                                     "--size-scale", "1.5", "--max-size", "0.15", "--stats"])
    case("cubes.off --dihedral-target 0", ["mesh", d("cubes.off"), "-o", "OUT", "-q",
                                           "--dihedral-target", "0", "--passes", "2"])
    # Failures: same message, same status.
    case("missing size array", ["mesh", d("sphere.off"), "-o", "OUT", "-q", "--size-array", "nope"])
    case("open box", ["mesh", os.path.join(data, "defects", "open-box.off"), "-o", "OUT", "-q"])
    case("NaN coordinate (ascii .vtp)", ["mesh", os.path.join(data, "defects", "nan-coordinate.vtp"),
                                         "-o", "OUT", "-q"])
    case("memory limit", ["mesh", d("cube.vtp"), "-o", "OUT", "-q", "--size", "0.02",
                          "--memory-limit", "100"])
    case("no such file", ["mesh", d("nosuch.off"), "-o", "OUT", "-q"])
    case("unwritable output", ["mesh", d("star.off"), "-o", os.path.join(tmp, "no-such-dir", "x.vtu"), "-q"])
    # .stl: read as vtkSTLReader with merging reads it (vertices merged when equal, -0 with
    # +0; facets that merge to fewer than 3 points dropped, their points kept; a binary file's
    # stored facet count ignored).
    case("sphere.stl (binary)", ["mesh", d("sphere.stl"), "-o", "OUT", "-q", "--stats"])
    case("sphere.stl boundary only", ["mesh", d("sphere.stl"), "-o", "OUT", "-q", "--boundary-only"])
    cube = cube_facets(0.0)
    signed = cube_facets(-0.0)
    mixed = os.path.join(tmp, "cube-signed-zeros.stl")
    write_binary_stl(mixed, [signed[i] if i % 3 == 0 else cube[i] for i in range(12)], count=7)
    case("cube.stl with -0 and +0 corners, wrong count", ["mesh", mixed, "-o", "OUT", "-q"])
    degenerate = os.path.join(tmp, "cube-degenerate-facets.stl")
    write_binary_stl(degenerate, cube[:5] + [((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
                                             ((0.5, 0.5, 2.0), (0.5, 0.5, 2.0), (0.5, 0.5, 2.0))]
                     + cube[5:])
    case("cube.stl with degenerate facets", ["mesh", degenerate, "-o", "OUT", "-q"])
    nan = os.path.join(tmp, "cube-nan.stl")
    write_binary_stl(nan, cube[:11] + [((float("nan"), 1.0, 1.0), cube[11][1], cube[11][2])])
    case("cube.stl with a NaN corner", ["mesh", nan, "-o", "OUT", "-q"])
    # ASCII .stl, by vtkSTLReader's grammar: keywords in any case, CRLF, "color" lines, several
    # solids, extra numbers after a vertex ignored, -0 merged with +0.
    def ascii_stl(path, solids, newline="\n", upper=False, extra=""):
        kw = (lambda w: w.upper()) if upper else (lambda w: w)
        with open(path, "w", newline="") as f:
            for name, facets in solids:
                f.write(kw("solid") + " " + name + newline)
                f.write("color 0.1 0.2 0.3" + newline)
                for facet in facets:
                    f.write(" " + kw("facet") + " normal 0 0 0" + newline + "  " + kw("outer") + " loop" + newline)
                    for corner in facet:
                        f.write("   " + kw("vertex") + " %r %r %.17e%s" % (corner[0], corner[1], corner[2], extra) + newline)
                    f.write("  " + kw("endloop") + newline + " " + kw("endfacet") + newline)
                f.write(kw("endsolid") + " " + name + newline + newline)
    plain = os.path.join(tmp, "cube-ascii.stl")
    ascii_stl(plain, [("cube", cube)])
    case("cube.stl, ASCII", ["mesh", plain, "-o", "OUT", "-q", "--stats"])
    dos = os.path.join(tmp, "cube-ascii-crlf.stl")
    ascii_stl(dos, [("top", signed[:6]), ("bottom", cube[6:])], newline="\r\n", upper=True, extra=" 7")
    case("cube.stl, ASCII: CRLF, upper case, 2 solids, -0", ["mesh", dos, "-o", "OUT", "-q"])
    ascii_nan = os.path.join(tmp, "cube-ascii-nan.stl")
    ascii_stl(ascii_nan, [("cube", cube[:11] + [((float("nan"), 1.0, 1.0), cube[11][1], cube[11][2])])])
    case("cube.stl, ASCII, a NaN corner", ["mesh", ascii_nan, "-o", "OUT", "-q"])
    # Left to VTK: an ASCII .stl VTK refuses (no endsolid) or whose line its buffer would split,
    # a binary one with a stray byte.
    unfinished = os.path.join(tmp, "cube-ascii-unfinished.stl")
    with open(plain) as f:
        text = f.read()
    with open(unfinished, "w") as f:
        f.write(text[:text.rindex("endsolid")])
    case("cube.stl, ASCII without endsolid (VTK path)", ["mesh", unfinished, "-o", "OUT", "-q"],
         expect_lean=False)
    long_line = os.path.join(tmp, "cube-ascii-long-name.stl")
    ascii_stl(long_line, [("x" * 300, cube)])
    case("cube.stl, ASCII with a 300-byte name (VTK path)", ["mesh", long_line, "-o", "OUT", "-q"],
         expect_lean=False)
    stray = os.path.join(tmp, "cube-stray-byte.stl")
    write_binary_stl(stray, cube, tail=b"x")
    case("cube.stl with a stray byte (VTK path)", ["mesh", stray, "-o", "OUT", "-q"], expect_lean=False)
    # Polygons: both paths triangulate them with triangulatePolygon.
    case("keyhole polygon", ["mesh", os.path.join(data, "defects", "keyhole-polygon.off"),
                             "-o", "OUT", "-q"])
    case("hole.off (quads)", ["mesh", d("hole.off"), "-o", "OUT", "-q", "--stats"])
    case("mpi.off (non-convex polygons) boundary only",
         ["mesh", d(os.path.join("invalid", "mpi.off")), "-o", "OUT", "-q", "--boundary-only"])
    case("double-torus-example.off (quads) boundary only",
         ["mesh", d("double-torus-example.off"), "-o", "OUT", "-q", "--boundary-only"])

if failures:
    print("\n\n".join(failures))
    print(f"TestLeanPath: {len(failures)} failure(s)")
    sys.exit(1)
print("TestLeanPath: all checks passed")
