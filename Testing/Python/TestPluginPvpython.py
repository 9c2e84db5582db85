"""The ParaView plugin in real pvpython: load TetMesher, apply the filter by its proxy name on
a real mesh, and check the numbers against an independent numpy implementation.

Usage: pvpython TestPluginPvpython.py PLUGIN_PATH DATA_DIR
"""
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import LoadPlugin, XMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy

plugin, data = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_quality import tet_quality  # noqa: E402

LoadPlugin(plugin, remote=False, ns=globals())
assert "TetQuality" in globals(), "the plugin did not define the TetQuality proxy"

reader = XMLUnstructuredGridReader(FileName=[os.path.join(data, "jittered-cube.vtu")])
quality = TetQuality(Input=reader)  # noqa: F821 (defined by LoadPlugin)
quality.NumberOfBins = 10
quality.UpdatePipeline()

mesh = servermanager.Fetch(quality, arg1=None, arg2=None, idx=0)
points = vtk_to_numpy(mesh.GetPoints().GetData())
tets = vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 4)
q_ref, min_ref, max_ref = tet_quality(points, tets)
q = vtk_to_numpy(mesh.GetCellData().GetArray("Quality"))
assert np.allclose(q, q_ref, atol=1e-12), np.abs(q - q_ref).max()
assert np.allclose(vtk_to_numpy(mesh.GetCellData().GetArray("MinDihedralAngle")), min_ref, atol=1e-9)

info = quality.GetDataInformation(0)
assert info.GetNumberOfCells() == 384
assert abs(mesh.GetFieldData().GetArray("QualityMinimum").GetValue(0) - q_ref.min()) < 1e-12

histogram = servermanager.Fetch(quality, arg1=None, arg2=None, idx=1)
counts = vtk_to_numpy(histogram.GetColumnByName("Count"))
assert (counts == np.histogram(q_ref, bins=10, range=(0, 1))[0]).all(), counts
# The mesher proxy on a real surface: the boundary of the result is exactly the input.
from paraview.simple import XMLPolyDataReader  # noqa: E402
from mesh_invariants import check_boundary_mesh, triangle_quality_caps  # noqa: E402

surface_reader = XMLPolyDataReader(FileName=[os.path.join(data, "..", "..", "Data", "torus.vtp")])
mesher = TetMesher(Input=surface_reader)  # noqa: F821 (defined by LoadPlugin)
mesher.UpdatePipeline()
surface = servermanager.Fetch(surface_reader)
tet_mesh = servermanager.Fetch(mesher, arg1=None, arg2=None, idx=0)
in_points = vtk_to_numpy(surface.GetPoints().GetData()).astype(np.float64)
in_triangles = vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).reshape(-1, 3)
out_points = vtk_to_numpy(tet_mesh.GetPoints().GetData())
out_tets = vtk_to_numpy(tet_mesh.GetCells().GetConnectivityArray()).reshape(-1, 4)
problems = check_boundary_mesh(in_points, in_triangles, out_points, out_tets)
assert not problems, problems
assert tet_mesh.GetCellData().GetArray("Quality") is not None
assert tet_mesh.GetCellData().GetArray("RegionId") is not None
# The surface's quality bound (2 sqrt(6) area / longest edge^2 of its worst triangle, capped at 1)
# in the field data, as numpy computes it.
caps = triangle_quality_caps(in_points, in_triangles)
bound = tet_mesh.GetFieldData().GetArray("SurfaceQualityBound").GetValue(0)
assert abs(bound - min(1.0, caps.min())) < 1e-12, (bound, caps.min())
print("TetMesher proxy: %d tets, boundary exact" % len(out_tets))

# HolePoints, TetGen's hole list as a repeated property: a point in the inner ball of nested
# spheres removes the ball (the volume is the outer shell's less the inner one's, exactly);
# emptied, the ball is a region of its own again (the clean command ran).
from mesh_invariants import enclosed_volume, shells  # noqa: E402

nested_reader = XMLPolyDataReader(FileName=[os.path.join(data, "..", "..", "Data", "nested_spheres.vtp")])
nested = servermanager.Fetch(nested_reader)
nested_points = vtk_to_numpy(nested.GetPoints().GetData()).astype(np.float64)
nested_triangles = vtk_to_numpy(nested.GetPolys().GetConnectivityArray()).reshape(-1, 3)
shell_volumes = sorted((enclosed_volume(nested_points, nested_triangles[s]) for s in shells(nested_triangles)),
                       reverse=True)
holed = TetMesher(Input=nested_reader, Refine=0, Optimize=0)  # noqa: F821
for hole_points, regions_expected, volume in (([0.01, 0.02, 0.03], 1, shell_volumes[0] - shell_volumes[1]),
                                              ([], 2, shell_volumes[0])):
    holed.HolePoints = hole_points
    holed.UpdatePipeline()
    result = servermanager.Fetch(holed, arg1=None, arg2=None, idx=0)
    result_tets = vtk_to_numpy(result.GetCells().GetConnectivityArray()).reshape(-1, 4)
    result_regions = vtk_to_numpy(result.GetCellData().GetArray("RegionId"))
    problems = check_boundary_mesh(nested_points, nested_triangles, vtk_to_numpy(result.GetPoints().GetData()),
                                   result_tets, result_regions, volume)
    assert not problems, (hole_points, problems)
    assert len(set(result_regions.tolist())) == regions_expected, (hole_points, set(result_regions.tolist()))
print("TetMesher proxy: HolePoints removes the inner ball, and emptied keeps it")

# RegionPoints, TetGen's region list (x y z attribute maxSize): a RegionAttribute cell array,
# the inner ball 5 and the shell 6 (largest + 1); emptied, no such array.
for region_points, expected in (([0.01, 0.02, 0.03, 5.0, 0.0], [5.0, 6.0]), ([], None)):
    holed.RegionPoints = region_points
    holed.UpdatePipeline()
    result = servermanager.Fetch(holed, arg1=None, arg2=None, idx=0)
    array = result.GetCellData().GetArray("RegionAttribute")
    got = None if array is None else sorted(set(vtk_to_numpy(array).tolist()))
    assert got == expected, (region_points, got)
print("TetMesher proxy: RegionPoints gives RegionAttribute, and emptied drops it")

# InteriorPoints (x y z per point, TetGen's -i list): output points n, n+1 after the n input
# points, bit for bit, and the boundary exact; emptied, the input points alone.
n_nested = len(nested_points)
for interior in ([0.01, 0.02, 0.03, 0.3, 0.2, 0.1], []):
    holed.InteriorPoints = interior
    holed.UpdatePipeline()
    result = servermanager.Fetch(holed, arg1=None, arg2=None, idx=0)
    result_points = vtk_to_numpy(result.GetPoints().GetData())
    result_tets = vtk_to_numpy(result.GetCells().GetConnectivityArray()).reshape(-1, 4)
    result_regions = vtk_to_numpy(result.GetCellData().GetArray("RegionId"))
    problems = check_boundary_mesh(nested_points, nested_triangles, result_points, result_tets,
                                   result_regions, shell_volumes[0])
    assert not problems, (interior, problems)
    assert len(result_points) == n_nested + len(interior) // 3, (interior, len(result_points))
    assert result_points[n_nested:].ravel().tolist() == interior, result_points[n_nested:]
print("TetMesher proxy: InteriorPoints are vertices n, n+1, and emptied none")

# InnerFacets: a square sheet inside a unit cube (four open edges) meshes only with it on, and
# then each sheet triangle is a face of two tets of the one region, through refinement.
import tempfile  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter  # noqa: E402
from paraview.simple import XMLPolyDataReader as SheetReader  # noqa: E402

corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1),
           (0.3, 0.3, 0.5), (0.7, 0.3, 0.5), (0.7, 0.7, 0.5), (0.3, 0.7, 0.5)]
sheet_triangles = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5),
                   (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7), (8, 9, 10), (8, 10, 11)]
sheet_points, sheet_cells = vtkPoints(), vtkCellArray()
for c in corners:
    sheet_points.InsertNextPoint(c)
for t in sheet_triangles:
    sheet_cells.InsertNextCell(3, t)
sheet_poly = vtkPolyData()
sheet_poly.SetPoints(sheet_points)
sheet_poly.SetPolys(sheet_cells)
with tempfile.TemporaryDirectory() as sheet_dir:
    sheet_file = os.path.join(sheet_dir, "sheet.vtp")
    sheet_writer = vtkXMLPolyDataWriter()
    sheet_writer.SetFileName(sheet_file)
    sheet_writer.SetInputData(sheet_poly)
    sheet_writer.Write()
    sheet_mesher = TetMesher(Input=SheetReader(FileName=[sheet_file]), SizeScale=0.1)  # noqa: F821
    for inner, meshed in ((0, False), (1, True)):
        sheet_mesher.InnerFacets = inner
        sheet_mesher.UpdatePipeline()
        result = servermanager.Fetch(sheet_mesher, arg1=None, arg2=None, idx=0)
        result_tets = vtk_to_numpy(result.GetCells().GetConnectivityArray()).reshape(-1, 4) \
            if result.GetNumberOfCells() else np.zeros((0, 4), dtype=np.int64)
        assert (len(result_tets) > 0) == meshed, (inner, len(result_tets))
        if meshed:
            result_regions = vtk_to_numpy(result.GetCellData().GetArray("RegionId"))
            faces = {}
            for t, tet in enumerate(result_tets.tolist()):
                for k in range(4):
                    faces.setdefault(tuple(sorted(tet[:k] + tet[k + 1:])), []).append(int(result_regions[t]))
            for tri in sheet_triangles[12:]:
                regions = faces.get(tuple(sorted(tri)), [])
                assert len(regions) == 2 and regions[0] == regions[1], (tri, regions)
            one_sided = sorted(f for f, r in faces.items() if len(r) == 1)
            assert one_sided == sorted(tuple(sorted(t)) for t in sheet_triangles[:12]), len(one_sided)
print("TetMesher proxy: InnerFacets keeps a sheet inside a cube as two inner faces, off refuses it")

print("TestPluginPvpython: ok, Q min %.4f mean %.4f" % (q_ref.min(), q_ref.mean()))
