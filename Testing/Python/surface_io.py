"""Reads the test surfaces into numpy arrays (points (n,3) float64, triangles (m,3))."""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy, numpy_to_vtk, numpy_to_vtkIdTypeArray
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData


def read_off(path):
    tokens = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0]
            tokens += line.split()
    assert tokens[0].endswith("OFF"), path
    n, m = int(tokens[1]), int(tokens[2])
    values = tokens[4:]
    points = np.array(values[:3 * n], dtype=np.float64).reshape(n, 3)
    faces, i = [], 3 * n
    for _ in range(m):
        k = int(values[i])
        faces.append([int(v) for v in values[i + 1:i + 1 + k]])
        i += 1 + k
    return points, np.array(faces, dtype=np.int64)


def read_vtp(path):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    poly = reader.GetOutput()
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
    triangles = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return points, triangles


def read_surface(path):
    return read_off(path) if path.endswith(".off") else read_vtp(path)


def to_polydata(points, triangles):
    poly = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    poly.SetPoints(pts)
    cells = vtkCellArray()
    offsets = numpy_to_vtkIdTypeArray(np.arange(0, 3 * len(triangles) + 1, 3, dtype=np.int64), deep=True)
    conn = numpy_to_vtkIdTypeArray(np.ascontiguousarray(triangles, dtype=np.int64).ravel(), deep=True)
    cells.SetData(offsets, conn)
    poly.SetPolys(cells)
    return poly


def grid_arrays(grid):
    points = vtk_to_numpy(grid.GetPoints().GetData())
    tets = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    return points, tets
