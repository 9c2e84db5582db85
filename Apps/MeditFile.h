// Medit's ASCII .mesh files (the format of MMG, CGAL's Mesh_3 output and FreeFEM, which TetGen
// also reads and writes), without VTK: the vertices and the first-order triangles,
// quadrilaterals and tetrahedra, with their references. One reader for `tetmesher mesh`
// (the surface: triangles and quadrilaterals) and `tetmesher quality` (the tetrahedra).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tetmesher
{
namespace cli
{

struct MeditMesh
{
  std::vector<double> points; // 3 per vertex, every vertex in file order
  // The surface's polygons in file order (a Triangles and a Quadrilaterals section in the
  // order the file has them): polygon i has the point ids (from 0)
  // polygonPoints[polygonOffsets[i], polygonOffsets[i + 1]).
  std::vector<std::int64_t> polygonOffsets{ 0 };
  std::vector<std::int64_t> polygonPoints;
  std::vector<std::int64_t> tetrahedra; // 4 point ids (from 0) per tetrahedron, file order
  std::vector<long> tetrahedronRefs;    // the reference of each tetrahedron
};

// Keywords are read case-insensitively, numbers wherever the lines break (the format is free);
// '#' starts a comment. Sections of other entities (edges, corners, ridges, normals, hexahedra,
// prisms, ...) are skipped by their known sizes. Throws FileError (SurfaceFiles.h) naming the
// file, the line and the defect: 2D meshes, second-order (curved) triangles or
// quadrilaterals, an unknown keyword, an index outside the vertices, a short section.
MeditMesh ReadMeditMesh(const std::string& path);

} // namespace cli
} // namespace tetmesher
