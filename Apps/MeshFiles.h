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

// Reads a triangulated surface. Throws FileError. `lists`, when given, receives TetGen's hole
// and region lists (SurfaceData's holePoints, regionPoints, regionMaxSizes; empty for other
// files).
vtkSmartPointer<vtkPolyData> ReadSurface(const std::string& path, SurfaceData* lists = nullptr);

// Writes an unstructured grid (.vtu or legacy .vtk by extension). Throws FileError.
// .vtu: raw appended binary, zlib-compressed when `compress`; .vtk: legacy binary.
void WriteVolumeMesh(vtkUnstructuredGrid* mesh, const std::string& path, bool compress = false);

} // namespace cli
} // namespace tetmesher
