// The input surface as the mesher sees it: triangles, their unique edges, and the structural
// checks that the recovery stage relies on (ids in range, no degenerate or duplicate
// triangle, no open edge). Geometric defects such as self-intersections are the business of
// SurfaceDiagnosis; if they slip through, recovery fails and names the item it could not
// recover.
#pragma once

#include "TetMesh.h"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tetmesher
{

struct SurfaceInput
{
  std::int32_t pointCount = 0;
  std::vector<std::array<VertexId, 3>> triangles;
  std::vector<std::array<VertexId, 2>> edges;  // unique, (a<b), sorted
  std::vector<std::int32_t> edgeFirstTriangle; // a triangle having each edge
  // The other triangle of an edge that has exactly two, else -1 (an interface edge).
  std::vector<std::int32_t> edgeSecondTriangle;
};

// Key of an unordered vertex pair / triple, for hashing.
inline std::uint64_t edgeKey(VertexId a, VertexId b)
{
  if (a > b)
    std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
    static_cast<std::uint32_t>(b);
}
// The three ids in increasing order (a sorting network: hot in look-ups by vertex triple).
inline std::array<VertexId, 3> sortedTriangle(VertexId a, VertexId b, VertexId c)
{
  if (b < a)
    std::swap(a, b);
  if (c < b)
    std::swap(b, c);
  if (b < a)
    std::swap(a, b);
  return { a, b, c };
}

// Builds the edge list and checks the structure. Returns an empty string on success, or a
// message naming the defect and the triangle/edge/point ids. An edge of one triangle is a
// defect unless openEdges (inner facets, MesherOptions::innerFacets): its second triangle is
// then -1, as for an edge of three or more.
std::string buildSurfaceInput(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount,
  SurfaceInput& out,
  bool openEdges = false);

} // namespace tetmesher
