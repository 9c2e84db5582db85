// Reading and writing the files the `tetmesher` command line accepts: whatever VTK reads
// (.vtu .vtk .vtp .stl .obj .ply), plus the formats of the meshers users compare us with:
// TetGen .node/.ele and Gmsh ASCII .msh (versions 2.2 and 4.1) meshes, TetGen .smesh .poly
// .face and Gmsh .msh surfaces, and .off surfaces.
#pragma once

#include "SurfaceFiles.h"

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkDataSet;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace tetmesher
{
namespace cli
{

// Reads a volume mesh. Throws FileError.
vtkSmartPointer<vtkDataSet> ReadVolumeMesh(const std::string& path);

// Reads a triangulated surface. Throws FileError. `notes`, when given, receives what the file
// holds but the mesh does not use (SolverSurfaceFiles.h), one line each; `holePoints` TetGen's
// hole list (3 doubles per point), `regionPoints` its region list (x, y, z, attribute).
vtkSmartPointer<vtkPolyData> ReadSurface(const std::string& path,
  std::string* notes = nullptr,
  std::vector<double>* holePoints = nullptr,
  std::vector<double>* regionPoints = nullptr);

// Writes an unstructured grid (.vtu or legacy .vtk by extension). Throws FileError.
// .vtu: raw appended binary, zlib-compressed when `compress`; .vtk: legacy binary.
void WriteVolumeMesh(vtkUnstructuredGrid* mesh, const std::string& path, bool compress = false);

} // namespace cli
} // namespace tetmesher
