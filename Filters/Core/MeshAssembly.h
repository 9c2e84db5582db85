// Conversion between the flat output arrays of a stage (points, 4 ids per tet, a region per
// tet) and a TetMesh with adjacency, so that later stages (interior refinement, quality
// optimisation) work on the mesh the boundary stage produced, with its boundary locked.
#pragma once

#include "TetMesh.h"

#include <cstdint>
#include <vector>

namespace tetmesher
{

// A tet mesh plus the region of each tet slot (kept in step by the stages that edit it).
struct RegionMesh
{
  TetMesh mesh;
  std::vector<std::int32_t> region; // per tet slot; meaningless for deleted slots
};

// Builds the adjacency of `tets` (positively oriented in TetMesh's convention). Faces with
// no neighbour (the boundary), faces between tets of different regions (interfaces) and the
// faces `inputFaces` names (4*t+f, -1 skipped: the input triangles, which include inner facets
// with one region on both sides) are marked constrained on both sides, so insertions and flips
// never cross or change them. Returns false if a face is shared by more than two tets, a tet
// names no point of `points`, or an input face no tet.
bool assembleRegionMesh(const std::vector<double>& points,
  const std::vector<std::int32_t>& tets,
  const std::vector<std::int32_t>& regionIds,
  RegionMesh& out,
  const std::vector<std::int32_t>& inputFaces = {});

// Writes the live tets of `in` back to flat arrays (deleted slots dropped, vertex ids kept).
void extractRegionMesh(const RegionMesh& in,
  std::vector<double>& points,
  std::vector<std::int32_t>& tets,
  std::vector<std::int32_t>& regionIds);

// For each tet face 4*t+f (face f opposite vertex f of tet t in `tets`), the input triangle
// with the same three vertices, or -1: both sides of an interface triangle name it.
std::vector<std::int32_t> tetFaceTriangles(const std::vector<std::int32_t>& tets,
  const std::int32_t* triangles,
  std::int32_t triangleCount);

// For each input triangle, 4*t+f of a tet face with the same three vertices (face f opposite
// vertex f of tet t), or -1 if no tet has it, from tetFaceTriangles' answer: the first found.
std::vector<std::int32_t> firstFaceOfTriangles(const std::vector<std::int32_t>& faceTriangle,
  std::int32_t triangleCount);

} // namespace tetmesher
