// Writing a tetrahedral mesh in the formats of the meshers users come from, for their solvers:
// Gmsh's ASCII .msh (version 2.2, which Gmsh, meshio, FEniCS's converters and ElmerGrid read),
// TetGen's .node/.ele/.face and Medit's ASCII .mesh (MMG's remeshers, FreeFEM). VTK-free: the
// lean command line and the VTK part both use it.
#pragma once

#include <cstdint>
#include <string>

namespace tetmesher
{
namespace cli
{

// A mesh to write: tets in VTK_TETRA order (positive volume), point ids from 0.
struct ExportMesh
{
  const double* points = nullptr; // xyz per point
  std::int64_t pointCount = 0;
  const std::int64_t* cells = nullptr; // 4 point ids per tet
  std::int64_t tetCount = 0;
  const std::int32_t* regionIds = nullptr; // per tet, or nullptr (all region 0)
  const double* regionAttribute = nullptr; // per tet (TetGen's region list), or nullptr
  // 4 per tet: the input cell whose triangle is the face opposite point i, or -1; nullptr: no
  // boundary faces are written.
  const std::int64_t* inputFaceIds = nullptr;
};

// True for the extensions WriteExportMesh handles: .msh, .node, .ele, .mesh.
bool IsExportExtension(const std::string& lowerExtension);

// Writes `mesh` to `path` by its extension. Coordinates are written in the shortest form that
// reads back to the same double. Every input triangle is written once, oriented out of the
// first tet (in order) that has it; a triangle between two regions is written once too.
//  .msh: Gmsh 2.2 ASCII; nodes numbered from 1; tets (type 4) with physical tag the region
//        attribute when every one is a whole number from 1 to 2^31 - 1, else RegionId + 1, and
//        elementary tag RegionId + 1; triangles (type 2) with physical tag 1 and elementary
//        tag the input cell id + 1.
//  .node or .ele: TetGen's NAME.node (numbered from 0), NAME.ele (attribute: the region
//        attribute, else RegionId) and NAME.face (marker: the input cell id + 1), NAME being
//        the path without extension.
//  .mesh: Medit ASCII (MeshVersionFormatted 2); vertices numbered from 1 with reference 0;
//        Tetrahedra with reference the region attribute when every one is a whole number
//        that fits an int, else RegionId + 1; Triangles with reference the input cell id + 1.
// Throws FileError (SurfaceFiles.h) when a file cannot be written.
void WriteExportMesh(const ExportMesh& mesh, const std::string& path);

} // namespace cli
} // namespace tetmesher
