"""vtkTetMesher through the Python package: exact boundary, exact volume, orientation,
regions, InputFaceIds, determinism and clear errors, on real and procedural surfaces.

Usage: /usr/bin/python3 TestTetMesherPython.py DATA_DIR
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints

from tetmesher import vtkTetMesher

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mesh_invariants import check_boundary_mesh, enclosed_volume, shells, triangle_quality_caps  # noqa: E402
from surface_io import grid_arrays, read_surface, to_polydata  # noqa: E402

data = sys.argv[1]
failures = []


def collect_errors(mesher):
    """The list the mesher's error messages will be appended to (and kept off the console)."""
    errors = []

    def on_error(obj, event, message):
        errors.append(message)
    on_error.CallDataType = "string0"
    mesher.AddObserver(vtkCommand.ErrorEvent, on_error)
    mesher.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda *a: None)
    return errors


def boundary_mesher(polydata):
    """A mesher of `polydata`'s boundary mesh alone (no refinement, no optimisation), and the
    list its error messages go to."""
    mesher = vtkTetMesher()
    mesher.SetInputData(polydata)
    mesher.SetRefine(False)
    mesher.SetOptimize(False)
    return mesher, collect_errors(mesher)


def mesh(points, triangles, **properties):
    mesher = vtkTetMesher()
    errors = collect_errors(mesher)
    poly = to_polydata(points, triangles)
    mesher.SetInputData(poly)
    for name, value in properties.items():
        getattr(mesher, "Set" + name)(value)
    mesher.Update()
    return mesher, errors


def check(name, expected_regions, volume="all", **properties):
    """volume: which shells the tets fill, exactly: "all" (one shell), "outer" (nested shells
    as regions: the outer shell's volume), "outer-inner" (nested shells as holes)."""
    points, triangles = read_surface(os.path.join(data, name))
    by_shell = sorted((enclosed_volume(points, triangles[s]) for s in shells(triangles)), reverse=True)
    expected_volume = {"all": sum(by_shell), "outer": by_shell[0],
                       "outer-inner": by_shell[0] - sum(by_shell[1:])}[volume]
    mesher, errors = mesh(points, triangles, **properties)
    if errors:
        failures.append(f"{name}: {errors}")
        return
    grid = mesher.GetOutput()
    out_points, tets = grid_arrays(grid)
    regions = vtk_to_numpy(grid.GetCellData().GetArray("RegionId"))
    problems = check_boundary_mesh(points, triangles, out_points, tets, regions, expected_volume)
    if len(set(regions.tolist())) != expected_regions:
        problems.append(f"{len(set(regions.tolist()))} regions, expected {expected_regions}")
    # InputFaceIds: face f (opposite point f) of a tet names the input triangle it lies on.
    face_ids = vtk_to_numpy(grid.GetCellData().GetArray("InputFaceIds")).reshape(-1, 4)
    named = 0
    for t, f in zip(*np.nonzero(face_ids >= 0)):
        face = sorted(int(tets[t][k]) for k in range(4) if k != f)
        if face != sorted(int(v) for v in triangles[face_ids[t][f]]):
            problems.append(f"InputFaceIds of tet {t} face {f} names the wrong triangle")
            break
        named += 1
    if named < len(triangles):
        problems.append(f"InputFaceIds names {named} tet faces for {len(triangles)} triangles")
    q = vtk_to_numpy(grid.GetCellData().GetArray("Quality"))
    # Exactly positive tets can still have Q = 0 in floating point (slivers of the boundary
    # mesh, which optimisation has not touched yet).
    if not (np.all(q >= 0) and np.all(q <= 1)):
        problems.append("Quality outside [0, 1]")
    # SurfaceQualityBound: 2 sqrt(6) area / longest edge^2 of the worst triangle (capped at 1),
    # which no tet on that triangle exceeds; numpy's own evaluation, to 1e-12.
    caps = triangle_quality_caps(points, triangles)
    bound = grid.GetFieldData().GetArray("SurfaceQualityBound").GetValue(0)
    worst = int(grid.GetFieldData().GetArray("SurfaceQualityBoundCellId").GetValue(0))
    if abs(bound - min(1.0, caps.min())) > 1e-12 * max(1.0, bound) or \
            (caps.min() < 1 and worst != int(caps.argmin())) or (caps.min() >= 1 and worst != -1):
        problems.append(f"SurfaceQualityBound {bound} (cell {worst}), numpy {caps.min()} (cell {caps.argmin()})")
    on_face = np.full(len(tets), np.inf)
    for t, f in zip(*np.nonzero(face_ids >= 0)):
        on_face[t] = min(on_face[t], caps[face_ids[t][f]])
    if np.any(q > on_face * (1 + 1e-12)):
        problems.append("a tet on an input triangle beats the triangle's quality bound")
    # Determinism: the same input gives the same mesh.
    again, _ = mesh(points, triangles, **properties)
    p2, t2 = grid_arrays(again.GetOutput())
    if not (np.array_equal(p2, out_points) and np.array_equal(t2, tets)):
        problems.append("a second run gave a different mesh")
    steiner = int(grid.GetFieldData().GetArray("SteinerPointCount").GetValue(0))
    print(f"{name}: {len(tets)} tets, {steiner} Steiner points, {len(set(regions.tolist()))} region(s)"
          + (f" -- {problems}" if problems else " -- exact"))
    if problems:
        failures.append(f"{name}: {problems}")


check("sphere.off", 1)
check("cube.vtp", 1)
check("joint.off", 1)
check("torus.vtp", 1)
check("nested_spheres.vtp", 2, volume="outer")
check("nested_spheres.vtp", 1, volume="outer-inner", EnclosedShellsAreHoles=True)
# TetGen's hole list: a point in the inner ball removes it, as EnclosedShellsAreHoles does.
hole = vtkPoints()
hole.InsertNextPoint(0.01, 0.02, 0.03)
check("nested_spheres.vtp", 1, volume="outer-inner", HolePoints=hole)
outside = vtkPoints()
outside.InsertNextPoint(3.0, 0.0, 0.0)
_, hole_errors = mesh(*read_surface(os.path.join(data, "nested_spheres.vtp")), HolePoints=outside)
if not any("hole point 0 (3, 0, 0) is outside the input surface" in e for e in hole_errors):
    failures.append(f"a hole point outside the surface: {hole_errors}")
# AddHolePoint / RemoveAllHolePoints (the plugin's HolePoints property): the list grows as a
# copy in doubles (the caller's vtkPoints never changes), and each change re-executes.
adder, add_errors = boundary_mesher(to_polydata(*read_surface(os.path.join(data, "nested_spheres.vtp"))))
adder.SetHolePoints(hole)
adder.Update()
with_hole = adder.GetOutput().GetNumberOfCells()
adder.AddHolePoint(3.0, 0.0, 0.0)
adder.Update()
named = any("hole point 1 (3, 0, 0) is outside the input surface" in e for e in add_errors)
adder.RemoveAllHolePoints()
adder.Update()
without = adder.GetOutput().GetNumberOfCells()
adder.AddHolePoint(0.01, 0.02, 0.03)
adder.Update()
added = adder.GetOutput().GetNumberOfCells()
if not (named and without > with_hole == added and hole.GetNumberOfPoints() == 1 and
        adder.GetHolePoints().GetDataType() == 11):  # VTK_DOUBLE
    failures.append(f"AddHolePoint: named {named}, tets {with_hole} / {without} / {added}, "
                    f"caller's points {hole.GetNumberOfPoints()}")

# AddRegionPoint / RemoveAllRegionPoints (TetGen's region list, the plugin's RegionPoints): a
# cell array RegionAttribute, the inner ball's tets 5 (their volume the inner shell's), the
# others 6 (largest + 1); without region points no such array; a point outside is named.
nested_points, nested_triangles = read_surface(os.path.join(data, "nested_spheres.vtp"))
inner_volume = min(enclosed_volume(nested_points, nested_triangles[sh]) for sh in shells(nested_triangles))
regioned, region_errors = boundary_mesher(to_polydata(nested_points, nested_triangles))
regioned.AddRegionPoint(0.01, 0.02, 0.03, 5.0)
regioned.Update()
grid = regioned.GetOutput()
attribute_array = grid.GetCellData().GetArray("RegionAttribute")
if attribute_array is None:
    failures.append("AddRegionPoint: no RegionAttribute array")
else:
    out_points, tets = grid_arrays(grid)
    attributes = vtk_to_numpy(attribute_array)
    a, b, c, d = (out_points[tets[:, k]] for k in range(4))
    volumes = np.abs(np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))) / 6
    ball = volumes[attributes == 5.0].sum()
    if sorted(set(attributes.tolist())) != [5.0, 6.0] or abs(ball - inner_volume) > 1e-9 * inner_volume:
        failures.append(f"AddRegionPoint: attributes {sorted(set(attributes.tolist()))}, "
                        f"ball volume {ball} vs {inner_volume}")
regioned.AddRegionPoint(3.0, 0.0, 0.0, 1.0)
regioned.Update()
if not any("region point 1 (3, 0, 0) is outside the input surface" in e for e in region_errors):
    failures.append(f"a region point outside the surface: {region_errors}")
regioned.RemoveAllRegionPoints()
regioned.Update()
if regioned.GetOutput().GetCellData().GetArray("RegionAttribute") is not None or \
        regioned.GetNumberOfRegionPoints() != 0:
    failures.append("RemoveAllRegionPoints: RegionAttribute is still there")
# With a max size (TetGen's region volume bound), refinement makes the ball finer.
regioned.SetRefine(True)
regioned.AddRegionPoint(0.01, 0.02, 0.03, 5.0)
regioned.Update()
plain_cells = regioned.GetOutput().GetNumberOfCells()
regioned.RemoveAllRegionPoints()
regioned.AddRegionPoint(0.01, 0.02, 0.03, 5.0, 0.05)
regioned.Update()
if not regioned.GetOutput().GetNumberOfCells() > 4 * plain_cells:
    failures.append(f"AddRegionPoint with a max size: {regioned.GetOutput().GetNumberOfCells()} "
                    f"tets against {plain_cells} without")

# Triangle strips (vtkStripper's output) are decomposed as vtkTriangleStrip does: the boundary
# is exactly the strips' triangles (their joints with a repeated point left out), the input
# cell ids are the strips', and the mesh has the torus's volume.
from vtkmodules.vtkFiltersCore import vtkStripper, vtkTriangleFilter  # noqa: E402
torus_points, torus_triangles = read_surface(os.path.join(data, "torus.vtp"))
stripper = vtkStripper()
stripper.SetInputData(to_polydata(torus_points, torus_triangles))
stripper.Update()
stripped = stripper.GetOutput()
expanded = vtkTriangleFilter()
expanded.SetInputData(stripped)
expanded.Update()
strip_triangles = vtk_to_numpy(expanded.GetOutput().GetPolys().GetConnectivityArray()).reshape(-1, 3)
striped, strip_errors = boundary_mesher(stripped)
striped.Update()
if stripped.GetNumberOfStrips() == 0 or strip_errors or striped.GetLastWarnings():
    # (A strip's every other triangle turned the wrong way would warn of the orientation.)
    failures.append(f"strips: {stripped.GetNumberOfStrips()} strips, errors {strip_errors}, "
                    f"warnings {striped.GetLastWarnings()}")
else:
    out_points, tets = grid_arrays(striped.GetOutput())
    problems = check_boundary_mesh(torus_points, strip_triangles, out_points, tets,
                                   vtk_to_numpy(striped.GetOutput().GetCellData().GetArray("RegionId")),
                                   enclosed_volume(torus_points, strip_triangles))
    face_ids = vtk_to_numpy(striped.GetOutput().GetCellData().GetArray("InputFaceIds"))
    used = set(face_ids[face_ids >= 0].tolist())
    if problems or len(strip_triangles) != len(torus_triangles) or \
            not used <= set(range(stripped.GetNumberOfCells())) or len(used) != stripped.GetNumberOfStrips():
        failures.append(f"strips: {problems}, {len(strip_triangles)} triangles from "
                        f"{stripped.GetNumberOfStrips()} strips, input cells named {len(used)}")

# Cell ids with strips among other cells: a vertex (cell 0), a triangle (cell 1) and a strip
# (cell 2) with a joint of a repeated point at its end make a tetrahedron: one tet, its
# bottom face from cell 1, its other three from cell 2, the joint left out.
from vtkmodules.vtkCommonCore import vtkIdList  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData  # noqa: E402
mixed = vtkPolyData()
corners = vtkPoints()
for x in ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)):
    corners.InsertNextPoint(*x)
mixed.SetPoints(corners)
for kind, ids in (("SetVerts", [0]), ("SetPolys", [0, 2, 1]), ("SetStrips", [0, 1, 3, 2, 0, 0])):
    cells = vtkCellArray()
    id_list = vtkIdList()
    for i in ids:
        id_list.InsertNextId(i)
    cells.InsertNextCell(id_list)
    getattr(mixed, kind)(cells)
one, one_errors = boundary_mesher(mixed)
one.Update()
faces = one.GetOutput().GetCellData().GetArray("InputFaceIds")
got = sorted(int(faces.GetComponent(0, k)) for k in range(4)) if faces and one.GetOutput().GetNumberOfCells() == 1 else None
if one_errors or got != [1, 2, 2, 2]:
    failures.append(f"a vertex, a triangle and a strip: errors {one_errors}, input cells of the faces {got}")

# The defects output draws a flagged triangle of a strip, not the whole strip: the stripped
# torus less its first strip is open, and every polygon of output 2 is a triangle.
open_strips = vtkPolyData()
open_strips.SetPoints(stripped.GetPoints())
kept_strips = vtkCellArray()
strip_ids = vtkIdList()
for c in range(1, stripped.GetNumberOfStrips()):
    stripped.GetCellPoints(c, strip_ids)
    kept_strips.InsertNextCell(strip_ids)
open_strips.SetStrips(kept_strips)
opened, open_errors = boundary_mesher(open_strips)
opened.Update()
open_defects = opened.GetDefectsOutput()
sizes = {open_defects.GetCell(c).GetNumberOfPoints() for c in range(open_defects.GetNumberOfCells())
         if open_defects.GetCellType(c) != 1}  # VTK_VERTEX
if not any("open edges" in e for e in open_errors) or sizes != {3}:
    failures.append(f"an open strip surface: errors {open_errors}, defect polygon sizes {sizes}")

# A CAD-like part whose recovery needs Steiner points (35-70): none may end up on a face.
check("gear.vtp", 1, Refine=False, Optimize=False)

# Size field: a constant size array, then a controlling space (an image of sizes).
def edge_lengths(points, tets):
    pairs = np.concatenate([tets[:, [i, j]] for i in range(4) for j in range(i + 1, 4)])
    pairs = np.unique(np.sort(pairs, axis=1), axis=0)
    return np.linalg.norm(points[pairs[:, 0]] - points[pairs[:, 1]], axis=1)


from vtkmodules.vtkCommonCore import vtkDoubleArray  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

points, triangles = read_surface(os.path.join(data, "cube.vtp"))
h = 0.1
poly = to_polydata(points, triangles)
sizes = vtkDoubleArray()
sizes.SetName("size")
sizes.SetNumberOfTuples(len(points))
sizes.Fill(h)
poly.GetPointData().AddArray(sizes)
mesher = vtkTetMesher()
mesher.SetInputData(poly)
mesher.SetSizeArrayName("size")
mesher.Update()
sized = mesher.GetOutput()
out_points, tets = grid_arrays(sized)
band = np.mean((edge_lengths(out_points, tets) / h >= 0.7) & (edge_lengths(out_points, tets) / h <= 1.42))
used = vtk_to_numpy(sized.GetPointData().GetArray("h"))
regular_tets = 1.0 / (h ** 3 / (6 * np.sqrt(2)))  # unit cube / volume of the regular tet of edge h
print(f"cube, h = {h}: {len(tets)} tets ({len(tets) / regular_tets:.2f} x the regular-tet count), "
      f"{100 * band:.1f}% of edges in [0.7, 1.42] h")
# The h used is h, raised (by under 1% here) only where the floor next to boundary faces
# larger than sqrt(2) h (cube.vtp's face diagonals are 2 h) lifts it.
if band < 0.8 or used.min() != h or used.max() > 1.02 * h:
    failures.append(f"constant size: {100 * band:.1f}% of edges in the band, h used {used.min()}..{used.max()}")
if not 0.8 < len(tets) / regular_tets < 1.5:
    failures.append(f"constant size: {len(tets)} tets, far from the regular-tet count {regular_tets:.0f}")
problems = check_boundary_mesh(points, triangles, out_points, tets)
if problems:
    failures.append(f"constant size: {problems}")

# Controlling space: an image over the cube whose size grows with x (0.06 .. 0.3).
space = vtkImageData()
space.SetDimensions(11, 2, 2)
space.SetOrigin(-0.5, -0.5, -0.5)
space.SetSpacing(0.2, 2, 2)
field = vtkDoubleArray()
field.SetName("h")
field.SetNumberOfTuples(space.GetNumberOfPoints())
for i in range(space.GetNumberOfPoints()):
    field.SetValue(i, 0.06 + 0.12 * space.GetPoint(i)[0] + 0.06 * 0.5 * 2)
space.GetPointData().AddArray(field)
mesher = vtkTetMesher()
mesher.SetInputData(to_polydata(points, triangles))
mesher.SetInputData(1, space)
mesher.Update()
graded = mesher.GetOutput()
gp, gt = grid_arrays(graded)
gh = vtk_to_numpy(graded.GetPointData().GetArray("h"))
left, right = gp[:, 0] < 0.2, gp[:, 0] > 0.8
if not (gh[left].mean() < gh[right].mean()) or len(gt) <= len(tets) * 0.2:
    failures.append("controlling space: sizes do not follow the image")
print(f"controlling space: {len(gt)} tets, mean h {gh[left].mean():.3f} (x < 0.2) vs {gh[right].mean():.3f} (x > 0.8)")
problems = check_boundary_mesh(points, triangles, gp, gt)
if problems:
    failures.append(f"controlling space: {problems}")

# Boundary only: no interior points, the paper's figure 2.
mesher = vtkTetMesher()
mesher.SetInputData(to_polydata(points, triangles))
mesher.RefineOff()
mesher.OptimizeOff()
mesher.Update()
if mesher.GetOutput().GetNumberOfPoints() != len(points):
    failures.append("RefineOff: the boundary mesh has interior points")

# Bad input: an open surface is refused, and the message names the open edges.
points, triangles = read_surface(os.path.join(data, "sphere.off"))
mesher, errors = mesh(points, triangles[1:])
if not errors or "open edge" not in errors[0]:
    failures.append(f"open surface: expected an 'open edge' error, got {errors}")
elif mesher.GetOutput().GetNumberOfCells() != 0:
    failures.append("open surface: a partial mesh was returned")
else:
    print("open surface refused:", errors[0].splitlines()[1][:100])
    # The defects output shows the triangles on the open edges, by input cell id.
    defects = mesher.GetDefectsOutput()
    labels = defects.GetCellData().GetAbstractArray("Defect")
    cells = vtk_to_numpy(defects.GetCellData().GetArray("InputCellId"))
    if defects.GetNumberOfCells() == 0 or any(labels.GetValue(i) != "open edge" for i in range(labels.GetNumberOfValues())):
        failures.append("open surface: the defects output does not show the open edges")
    # Removing triangle 0 opened the edges of its 3 neighbours; their ids (in the shortened
    # list) are what the output names.
    removed = set(int(v) for v in triangles[0])
    for c in cells:
        if len(removed & set(int(v) for v in triangles[1:][c])) < 2:
            failures.append(f"defects output names triangle {c}, not next to the hole")
    if mesher.GetLastError().find("open edge") < 0:
        failures.append("GetLastError() does not name the open edges")

# A size field beyond the memory limit: refused before refinement, with the estimate named;
# no mesh.
points, triangles = read_surface(os.path.join(data, "cube.vtp"))
mesher, errors = mesh(points, triangles, MemoryLimit=10.0, SizeScale=0.05)
if not errors or "more than the memory limit of 10 MB" not in mesher.GetLastError():
    failures.append(f"MemoryLimit 10 MB: expected a refusal naming the limit, got {errors}")
elif mesher.GetOutput().GetNumberOfCells() != 0:
    failures.append("MemoryLimit: a mesh was returned with the error")
else:
    print("memory limit:", mesher.GetLastError()[:140])

# AddInteriorPoint (TetGen's -i list, the plugin's InteriorPoints): on anchor.off, whose boundary
# mesh has Steiner points, a point inside (the centroid of the boundary mesh's largest tet) is
# output point n, bit for bit, before the Steiner points, and the boundary stays exact, through
# the full pipeline too; a point outside is named; RemoveAllInteriorPoints empties the list.
anchor_points, anchor_triangles = read_surface(os.path.join(data, "anchor.off"))
n_anchor = len(anchor_points)
pointed, point_errors = boundary_mesher(to_polydata(anchor_points, anchor_triangles))
pointed.Update()
plain_points, plain_tets = grid_arrays(pointed.GetOutput())
a, b, c, d = (plain_points[plain_tets[:, k]] for k in range(4))
largest = np.argmax(np.abs(np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))))
inside = [float(x) for x in plain_points[plain_tets[largest]].mean(axis=0)]
pointed.AddInteriorPoint(*inside)
for refine in (False, True):
    pointed.SetRefine(refine)
    pointed.SetOptimize(refine)
    pointed.Update()
    got_points, got_tets = grid_arrays(pointed.GetOutput())
    problems = check_boundary_mesh(anchor_points, anchor_triangles, got_points, got_tets)
    if problems or got_points[n_anchor].tolist() != inside or n_anchor not in set(got_tets.ravel().tolist()) \
            or len(got_points) <= n_anchor + 1 or pointed.GetNumberOfInteriorPoints() != 1:
        failures.append(f"AddInteriorPoint (refine {refine}): {problems}, point n {got_points[n_anchor].tolist()} "
                        f"vs {inside}, {len(got_points)} points")
pointed.AddInteriorPoint(100.0, 0.0, 0.0)
pointed.Update()
if not any("interior point 1 (100, 0, 0) is outside the meshed domain" in e for e in point_errors):
    failures.append(f"an interior point outside the surface: {point_errors}")
pointed.RemoveAllInteriorPoints()
pointed.Update()
if pointed.GetNumberOfInteriorPoints() != 0 or pointed.GetOutput().GetNumberOfCells() == 0:
    failures.append("RemoveAllInteriorPoints: the list is not empty, or no mesh")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("TestTetMesherPython: all checks passed")
