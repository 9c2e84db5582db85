"""Every file of Testing/Data/defects through the three faces of the product: the exact
diagnosis text and ids through `tetmesher mesh` (exit status 1, message on stderr, no output
file), through vtkTetMesher in Python (GetLastError(), the defects output's cells with their
Defect labels and InputCellId), and through the TetMesher proxy in pvpython (the defects
output port and its DefectSummary) when a pvpython is given. The two valid controls (cubes
sharing a face, cubes touching along an edge) must mesh into two regions; a cube with a
flipped triangle (a warning: the mesh does not depend on orientation) into one, with the
warning on stderr and in the defects output.

Usage: /usr/bin/python3 TestDefects.py TETMESHER DEFECTS_DIR [PVPYTHON PVPYTHON_PATH PLUGIN]
       (with PYTHONPATH holding the built `tetmesher` package)
       /usr/bin/python3 TestDefects.py --cli-only TETMESHER DEFECTS_DIR   (no Python module:
       for a sanitizer build, whose module an uninstrumented Python cannot load)
Inside pvpython (run by the above): pvpython TestDefects.py --pvpython PLUGIN VTP_DIR
"""
import os
import subprocess
import sys
import tempfile

PREFIX = "the input surface cannot be meshed:\n"
POLYGON_NOTE = ("\n(triangle ids count the triangles of the input's polygons and strips in order; "
                "input cell ids differ when the input has vertices, lines, polygons or strips)")
# After open or non-manifold edges: how to keep inner facets (SurfaceMeshing.cxx).
FACET_NOTE = ("\n(a surface with a hole must be closed; triangles with the volume on both sides, such "
              "as a sheet or a fin inside it, are kept with --inner-facets, the InnerFacets property)")
INTERSECTING_CUBE_PAIRS = [(2, 16), (2, 17), (2, 22), (3, 17), (3, 22), (3, 23), (6, 12),
                           (6, 13), (6, 16), (7, 12), (7, 16), (7, 17), (8, 13), (8, 22),
                           (9, 12), (9, 13), (9, 22), (9, 23)]

# name -> (summary, polygon note?, cells of the defects output as (Defect label, InputCellId),
# in output order: the diagnosis' records in order, each record's triangles in order, lone
# points (InputCellId -1) first). summary None: a valid surface, meshed into `regions`.
CASES = {
    "open-box.off": (
        "4 open edges (points 4-5, 4-7, 5-6, 6-7; triangles 3, 9, 5, 7)", False,
        [("open edge", c) for c in (3, 9, 5, 7)]),
    # Valid, with a warning (WARNINGS): orientation does not matter to the mesh.
    "flipped-triangle.off": (None, False, 1),
    "intersecting-cubes.off": (
        "18 intersecting triangle pairs (triangles 2-16, 2-17, 2-22, 3-17, 3-22, 3-23, 6-12, "
        "6-13, 6-16, 7-12, ...)", False,
        [("intersecting triangle pair", c) for pair in INTERSECTING_CUBE_PAIRS for c in pair]),
    "duplicate-triangles.off": (
        "1 duplicated triangle (points 4-6-7; triangles 3=12)", False,
        [("duplicated triangle", 3), ("duplicated triangle", 12)]),
    # The zero-area triangle 0-4-1 lies along the edge 0-1 of triangle 2, so the triangles
    # 0 (0-2-4) and 1 (4-2-1) meet triangle 2 along a segment that is not an edge they share.
    "zero-area-triangle.off": (
        "1 degenerate (zero-area) triangle (points 0-4-1; triangles 5)\n"
        "2 intersecting triangle pairs (triangles 0-2, 1-2)", False,
        [("degenerate (zero-area) triangle", 5)] +
        [("intersecting triangle pair", c) for c in (0, 2, 1, 2)]),
    "nan-coordinate.vtp": (
        "1 point with non-finite coordinates (point 6)", False,
        [("point with non-finite coordinates", -1)]),
    "huge-coordinate.off": (
        "1 point with coordinates too large or too small to decide exactly (magnitudes beyond "
        "1e-40..1e50; scale the model) (point 6)", False,
        [("point with coordinates too large or too small to decide exactly (magnitudes beyond "
          "1e-40..1e50; scale the model)", -1)]),
    "outlying-point.off": (
        "1 point out of all proportion to the surface (farther from its median point than 1e15 "
        "times its shortest edge: a corrupted coordinate?) (point 6)", False,
        [("point out of all proportion to the surface (farther from its median point than "
          "1e15 times its shortest edge: a corrupted coordinate?)", -1)]),
    # One polygon (cell 10) around a square hole through a slit: its triangles (8, by
    # triangulatePolygon) cover the top around the hole once and leave the hole's rim open.
    # (VTK's vtkPolygon, used until 2026-11-29, also made two zero-area triangles on the slit
    # and 12 intersecting pairs.)
    "keyhole-polygon.off": (
        "4 open edges (points 8-9, 8-11, 9-10, 10-11; triangles 17, 12, 16, 14)", True,
        [("open edge", 10)] * 4),
    # Valid: two regions sharing a face (a multi-material interface) ...
    "cubes-sharing-face.off": (None, False, 2),
    # ... and two cubes touching along one edge only: every triangle on that edge (4 of
    # them) has a cube on one side and the outside on the other, so the diagnosis accepts
    # the non-manifold edge, and the mesher gives two regions that share the edge.
    "cubes-sharing-edge.off": (None, False, 2),
}

# Valid surfaces with warnings: name -> (DefectSummary, defects output cells as in CASES).
WARNINGS = {
    "flipped-triangle.off": (
        "3 edges with inconsistently oriented triangles (points 0-4, 0-5, 4-5; "
        "triangles 5, 10, 4, 2)",
        [("edge with inconsistently oriented triangles", c) for c in (5, 10, 4, 5, 2, 5)]),
}

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def expected_error(name):
    summary, note, _ = CASES[name]
    facets = "open edge" in summary or "non-manifold edge" in summary
    return PREFIX + summary + (POLYGON_NOTE if note else "") + (FACET_NOTE if facets else "")


def read_surface(path):
    """A .off as vtkPolyData with its polygons as they are (the filter triangulates them)."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    if path.endswith(".vtp"):
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(path)
        reader.Update()
        return reader.GetOutput()
    tokens = []
    with open(path) as f:
        for line in f:
            tokens += line.split("#")[0].split()
    n, m = int(tokens[1]), int(tokens[2])
    i = 4
    points = vtkPoints()
    points.SetDataTypeToDouble()
    for _ in range(n):
        points.InsertNextPoint(*[float(x) for x in tokens[i:i + 3]])
        i += 3
    cells = vtkCellArray()
    for _ in range(m):
        k = int(tokens[i])
        cells.InsertNextCell(k, [int(x) for x in tokens[i + 1:i + 1 + k]])
        i += 1 + k
    poly = vtkPolyData()
    poly.SetPoints(points)
    poly.SetPolys(cells)
    return poly


def defect_cells(defects):
    data = defects.GetCellData()
    labels, cells = data.GetAbstractArray("Defect"), data.GetArray("InputCellId")
    if defects.GetNumberOfCells() and (labels is None or cells is None):
        return "no Defect or InputCellId array"
    return [(labels.GetValue(i), int(cells.GetValue(i))) for i in range(defects.GetNumberOfCells())]


def check_defects_output(where, name, defects):
    summary, _, cells = CASES[name]
    if summary is None:  # a valid surface: its warnings, if any
        summary, cells = WARNINGS.get(name, (None, []))
    got = defect_cells(defects)
    check(got == cells, f"{where} {name}: defects output cells\n  got      {got}\n  expected {cells}")
    array = defects.GetFieldData().GetAbstractArray("DefectSummary")
    got_summary = array.GetValue(0) if array is not None else None
    check(got_summary == summary, f"{where} {name}: DefectSummary {got_summary!r}, expected {summary!r}")


def test_cli(tetmesher, folder):
    with tempfile.TemporaryDirectory() as tmp:
        for name, (summary, _, extra) in CASES.items():
            path = os.path.join(folder, name)
            out = os.path.join(tmp, name + ".vtu")
            result = subprocess.run([tetmesher, "mesh", path, "-o", out, "-q"],
                                    capture_output=True, text=True, timeout=300)
            if summary is None:
                check(result.returncode == 0 and os.path.exists(out),
                      f"CLI {name}: status {result.returncode}, stderr {result.stderr!r}")
                warning = WARNINGS.get(name, ("", []))[0]
                expected = "".join(f"tetmesher: {path}: warning: {line}\n"
                                   for line in warning.split("\n") if line)
                check(result.stderr == expected,
                      f"CLI {name}: stderr\n{result.stderr!r}\nexpected\n{expected!r}")
                continue
            expected = f"tetmesher: {path}: {expected_error(name)}\n"
            check(result.returncode == 1, f"CLI {name}: exit status {result.returncode}, expected 1")
            check(result.stderr == expected,
                  f"CLI {name}: stderr\n{result.stderr!r}\nexpected\n{expected!r}")
            check(not os.path.exists(out), f"CLI {name}: an output file was written")


def test_python(folder):
    from vtkmodules.vtkCommonCore import vtkObject
    from tetmesher import vtkTetMesher
    vtkObject.GlobalWarningDisplayOff()  # the filter's vtkErrorMacro is expected here
    for name, (summary, _, extra) in CASES.items():
        mesher = vtkTetMesher()
        mesher.SetInputData(read_surface(os.path.join(folder, name)))
        mesher.Update()
        mesh, defects = mesher.GetOutput(), mesher.GetDefectsOutput()
        if summary is None:
            check(mesher.GetLastError() in ("", None), f"Python {name}: {mesher.GetLastError()!r}")
            warning = WARNINGS.get(name, ("", []))[0]
            check(mesher.GetLastWarnings() == warning,
                  f"Python {name}: GetLastWarnings() {mesher.GetLastWarnings()!r}, expected {warning!r}")
            regions = mesh.GetCellData().GetArray("RegionId")
            check(mesh.GetNumberOfCells() > 0 and regions is not None and
                  regions.GetRange() == (0.0, extra - 1.0),
                  f"Python {name}: expected a mesh with {extra} regions")
            check_defects_output("Python", name, defects)
            continue
        check(mesher.GetLastError() == expected_error(name),
              f"Python {name}: GetLastError()\n{mesher.GetLastError()!r}\nexpected\n{expected_error(name)!r}")
        check(mesh.GetNumberOfCells() == 0, f"Python {name}: a mesh came out of defective input")
        check_defects_output("Python", name, defects)
        # The defect cells are the input's cells, point for point.
        surface = read_surface(os.path.join(folder, name))
        for i in range(defects.GetNumberOfCells()):
            cell = int(defects.GetCellData().GetArray("InputCellId").GetValue(i))
            got = [defects.GetCell(i).GetPointId(k) for k in range(defects.GetCell(i).GetNumberOfPoints())]
            if cell >= 0:
                want = [surface.GetCell(cell).GetPointId(k) for k in range(surface.GetCell(cell).GetNumberOfPoints())]
                check(got == want, f"Python {name}: defect cell {i} has points {got}, input cell {cell} {want}")


def write_vtp_copies(folder, tmp):
    """pvpython has no OFF reader: hand it every case as .vtp (polygons kept)."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    for name in CASES:
        writer = vtkXMLPolyDataWriter()
        writer.SetInputData(read_surface(os.path.join(folder, name)))
        writer.SetFileName(os.path.join(tmp, os.path.splitext(name)[0] + ".vtp"))
        writer.SetDataModeToAscii()
        writer.Write()


def test_pvpython(pvpython, pvpython_path, plugin, folder):
    with tempfile.TemporaryDirectory() as tmp:
        write_vtp_copies(folder, tmp)
        env = dict(os.environ, PYTHONPATH=pvpython_path)
        result = subprocess.run([pvpython, "--force-offscreen-rendering", os.path.abspath(__file__),
                                 "--pvpython", plugin, tmp], capture_output=True, text=True,
                                env=env, timeout=600)
        print(result.stdout, end="")
        check(result.returncode == 0 and "pvpython: ok" in result.stdout,
              f"pvpython: status {result.returncode}\n{result.stdout}\n{result.stderr[-4000:]}")


def run_in_pvpython(plugin, vtp_dir):
    from paraview.simple import LoadPlugin, XMLPolyDataReader
    LoadPlugin(plugin, remote=False, ns=globals())
    ports = globals()["TetMesher"]().GetClientSideObject().GetNumberOfOutputPorts()
    if ports < 3:
        print(f"pvpython: the plugin {plugin} has {ports} output ports, not 3 (Mesh, Quality "
              "Histogram, Input Defects): it is older than the defects output, rebuild it")
        sys.exit(1)
    for name, (summary, _, extra) in CASES.items():
        reader = XMLPolyDataReader(FileName=[os.path.join(vtp_dir, os.path.splitext(name)[0] + ".vtp")])
        mesher = globals()["TetMesher"](Input=reader)
        mesher.UpdatePipeline()
        # Built-in session: the filter's outputs directly (servermanager.Fetch cannot fetch
        # the outputs of a filter whose request failed).
        algorithm = mesher.GetClientSideObject()
        mesh, defects = algorithm.GetOutputDataObject(0), algorithm.GetOutputDataObject(2)
        if summary is None:
            regions = mesh.GetCellData().GetArray("RegionId")
            check(regions is not None and regions.GetRange() == (0.0, extra - 1.0),
                  f"pvpython {name}: expected a mesh with {extra} regions")
            check_defects_output("pvpython", name, defects)
        else:
            check(mesh.GetNumberOfCells() == 0, f"pvpython {name}: a mesh came out of defective input")
            check_defects_output("pvpython", name, defects)
    if failures:
        print("\n".join(failures))
        sys.exit(1)
    print(f"TestDefects pvpython: ok, {len(CASES)} surfaces through the TetMesher proxy")


def main():
    if sys.argv[1] == "--pvpython":
        run_in_pvpython(sys.argv[2], sys.argv[3])
        return
    cli_only = sys.argv[1] == "--cli-only"
    if cli_only:
        del sys.argv[1]
    tetmesher, folder = sys.argv[1], sys.argv[2]
    present = sorted(f for f in os.listdir(folder) if not f.endswith(".py"))
    check(present == sorted(CASES), f"defect files {present} differ from the cases {sorted(CASES)}")
    test_cli(tetmesher, folder)
    if cli_only:
        if failures:
            print("\n\n".join(failures))
            sys.exit(1)
        print(f"TestDefects: ok, {len(CASES)} surfaces through the CLI")
        return
    test_python(folder)
    if len(sys.argv) >= 6 and sys.argv[3] and sys.argv[5]:
        test_pvpython(sys.argv[3], sys.argv[4], sys.argv[5], folder)
    else:
        print("TestDefects: no pvpython given, the ParaView part is skipped")
    if failures:
        print("\n\n".join(failures))
        sys.exit(1)
    print(f"TestDefects: ok, {len(CASES)} surfaces through the CLI and vtkTetMesher")


if __name__ == "__main__":
    main()
