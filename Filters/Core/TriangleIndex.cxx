#include "TriangleIndex.h"

#include <algorithm>

namespace tetmesher
{

static_assert(sizeof(std::array<VertexId, 3>) == 3 * sizeof(VertexId),
  "a vector of vertex triples is a flat array of ids");

TriangleIndex::TriangleIndex(const std::vector<std::array<VertexId, 3>>& triangles)
  : TriangleIndex(triangles.empty() ? nullptr : triangles[0].data(),
      static_cast<std::int32_t>(triangles.size()))
{
}

TriangleIndex::TriangleIndex(const std::int32_t* triangles, std::int32_t triangleCount)
{
  VertexId maxVertex = -1;
  for (std::int64_t i = 0; i < 3 * static_cast<std::int64_t>(triangleCount); ++i)
    maxVertex = std::max(maxVertex, triangles[i]);
  start_.assign(static_cast<std::size_t>(maxVertex) + 2, 0);
  for (std::int32_t i = 0; i < triangleCount; ++i)
  {
    const std::int32_t* t = triangles + 3 * static_cast<std::size_t>(i);
    ++start_[static_cast<std::size_t>(std::min({ t[0], t[1], t[2] })) + 1];
  }
  for (std::size_t v = 0; v + 1 < start_.size(); ++v)
    start_[v + 1] += start_[v];
  others_.resize(static_cast<std::size_t>(triangleCount));
  triangle_.resize(static_cast<std::size_t>(triangleCount));
  std::vector<std::int32_t> next(start_.begin(), start_.end() - 1);
  for (std::int32_t i = 0; i < triangleCount; ++i)
  {
    const std::int32_t* t = triangles + 3 * static_cast<std::size_t>(i);
    const auto sorted = sortedTriangle(t[0], t[1], t[2]);
    const std::int32_t k = next[static_cast<std::size_t>(sorted[0])]++;
    others_[k] = { sorted[1], sorted[2] };
    triangle_[k] = i;
  }
}

} // namespace tetmesher
