// Input triangles by their vertex sets: which triangle has the vertices {a, b, c}.
#pragma once

#include "SurfaceInput.h"
#include "TetMesh.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace tetmesher
{

// Triangles grouped by their smallest vertex (counting sort), each with its other two sorted:
// a look-up scans the few triangles of one vertex. Several times faster to build and to query
// than a std::map or hash map of vertex triples on the 10^5 triangles of big surfaces.
class TriangleIndex
{
public:
  // `triangles`: 3 vertex ids (>= 0) per triangle.
  TriangleIndex(const std::int32_t* triangles, std::int32_t triangleCount);
  explicit TriangleIndex(const std::vector<std::array<VertexId, 3>>& triangles);

  // The lowest id of a triangle with vertices {a, b, c} (any order), or -1.
  std::int32_t find(VertexId a, VertexId b, VertexId c) const
  {
    const auto k = sortedTriangle(a, b, c);
    if (k[0] < 0 || static_cast<std::size_t>(k[0]) + 1 >= start_.size())
      return -1;
    for (std::int32_t e = start_[k[0]]; e < start_[k[0] + 1]; ++e)
      if (others_[e][0] == k[1] && others_[e][1] == k[2])
        return triangle_[e];
    return -1;
  }

  // The largest vertex id of the triangles (-1 for none).
  VertexId largestVertex() const { return static_cast<VertexId>(start_.size()) - 2; }

private:
  std::vector<std::int32_t> start_;             // entries of vertex v: [start_[v], start_[v+1])
  std::vector<std::array<VertexId, 2>> others_; // per entry, the other two vertices, sorted
  std::vector<std::int32_t> triangle_;          // per entry, the triangle id (increasing)
};

} // namespace tetmesher
