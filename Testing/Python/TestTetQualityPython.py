"""vtkTetQuality through the wrapped Python package `tetmesher` (run with /usr/bin/python3).

Checks the Quality and dihedral arrays against an independent numpy implementation, the
summary in the field data, the histogram, and that bad input raises a clear error.
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

import tetmesher
from tetmesher import vtkTetQuality

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference_quality import tet_quality  # noqa: E402

data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Data")

reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(os.path.join(data, "jittered-cube.vtu"))
quality = vtkTetQuality()
quality.SetInputConnection(reader.GetOutputPort())
quality.SetNumberOfBins(10)
quality.Update()
mesh = quality.GetOutput()

points = vtk_to_numpy(mesh.GetPoints().GetData())
tets = vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 4)
q_ref, min_ref, max_ref = tet_quality(points, tets)
q = vtk_to_numpy(mesh.GetCellData().GetArray("Quality"))
assert np.allclose(q, q_ref, rtol=0, atol=1e-12), np.abs(q - q_ref).max()
assert np.allclose(vtk_to_numpy(mesh.GetCellData().GetArray("MinDihedralAngle")), min_ref, atol=1e-9)
assert np.allclose(vtk_to_numpy(mesh.GetCellData().GetArray("MaxDihedralAngle")), max_ref, atol=1e-9)

field = mesh.GetFieldData()
assert field.GetArray("TetrahedronCount").GetValue(0) == len(tets) == 384
assert abs(field.GetArray("QualityMinimum").GetValue(0) - q_ref.min()) < 1e-12
assert abs(field.GetArray("QualityMean").GetValue(0) - q_ref.mean()) < 1e-12
assert field.GetArray("QualityShareBelow0.3").GetValue(0) == np.mean(q_ref < 0.3)

histogram = quality.GetHistogramOutput()
counts = vtk_to_numpy(histogram.GetColumnByName("Count"))
assert histogram.GetNumberOfRows() == 10
assert counts.sum() == len(tets)
assert (counts == np.histogram(q_ref, bins=10, range=(0, 1))[0]).all(), counts

# Bad input: no tetrahedra -> the filter fails with a message naming the defect.
from vtkmodules.vtkCommonCore import vtkCommand  # noqa: E402
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402

messages = []


def on_error(obj, event, message):
    messages.append(message)


on_error.CallDataType = "string0"
sphere = vtkSphereSource()  # keep a reference: the pipeline does not own its sources
bad = vtkTetQuality()
bad.SetInputConnection(sphere.GetOutputPort())
bad.AddObserver(vtkCommand.ErrorEvent, on_error)
bad.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda *args: None)  # its echo
assert bad.GetExecutive().Update() == 0
assert any("no tetrahedra" in m for m in messages), messages
print("TestTetQualityPython: ok,", tetmesher.__name__, "Q min %.4f" % q_ref.min())
