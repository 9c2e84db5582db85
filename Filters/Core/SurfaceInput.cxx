#include "SurfaceInput.h"

#include "Predicates.h"
#include "RadixSort.h"
#include "TriangleIndex.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace tetmesher
{

std::string buildSurfaceInput(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount,
  SurfaceInput& out,
  bool openEdges)
{
  std::ostringstream error;
  out = SurfaceInput();
  out.pointCount = pointCount;
  if (pointCount < 4 || triangleCount < 4 || !points || !triangles)
    return "empty input: a closed surface needs at least 4 points and 4 triangles";
  std::string rangeError = predicates::coordinateRangeError(points, pointCount, "point");
  if (!rangeError.empty())
    return rangeError;
  std::vector<std::pair<std::uint64_t, std::int32_t>> edgeUses;
  edgeUses.reserve(3 * static_cast<std::size_t>(triangleCount));
  out.triangles.reserve(triangleCount);
  // The first triangle with an id out of range or degenerate, and its message.
  std::int32_t firstBad = triangleCount;
  for (std::int32_t t = 0; t < triangleCount && firstBad == triangleCount; ++t)
  {
    std::array<VertexId, 3> v = { triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2] };
    for (VertexId id : v)
    {
      if (firstBad == triangleCount && (id < 0 || id >= pointCount))
      {
        error << "triangle " << t << " references point id " << id << " out of range [0,"
              << pointCount << ")";
        firstBad = t;
      }
    }
    if (firstBad < triangleCount)
      break;
    const double* p[3] = { points + 3 * v[0], points + 3 * v[1], points + 3 * v[2] };
    bool collinear = predicates::orient2d(p[0], p[1], p[2], 0) == 0 &&
      predicates::orient2d(p[0], p[1], p[2], 1) == 0 &&
      predicates::orient2d(p[0], p[1], p[2], 2) == 0;
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] || collinear)
    {
      error << "triangle " << t << " (" << v[0] << "," << v[1] << "," << v[2] << ") is degenerate";
      firstBad = t;
      break;
    }
    out.triangles.push_back(v);
    for (int e = 0; e < 3; ++e)
      edgeUses.push_back({ edgeKey(v[e], v[(e + 1) % 3]), t });
  }
  // Duplicates among the triangles before it, reported as the triangle-by-triangle scan
  // would: at the first triangle that is not the lowest id with its vertices.
  {
    const TriangleIndex index(out.triangles);
    for (std::size_t t = 0; t < out.triangles.size(); ++t)
    {
      const auto& v = out.triangles[t];
      const std::int32_t first = index.find(v[0], v[1], v[2]);
      if (first != static_cast<std::int32_t>(t))
        return "triangles " + std::to_string(first) + " and " + std::to_string(t) +
          " are duplicates";
    }
  }
  if (firstBad < triangleCount)
    return error.str();
  sortPushedPairs(edgeUses);
  for (std::size_t i = 0; i < edgeUses.size();)
  {
    std::size_t j = i;
    while (j < edgeUses.size() && edgeUses[j].first == edgeUses[i].first)
      ++j;
    VertexId a = static_cast<VertexId>(edgeUses[i].first >> 32);
    VertexId b = static_cast<VertexId>(edgeUses[i].first & 0xffffffffu);
    if (j - i < 2 && !openEdges)
    {
      error << "open edge (" << a << "," << b << ") of triangle " << edgeUses[i].second
            << ": the surface must be closed";
      return error.str();
    }
    out.edges.push_back({ a, b });
    out.edgeFirstTriangle.push_back(edgeUses[i].second);
    out.edgeSecondTriangle.push_back(j - i == 2 ? edgeUses[i + 1].second : -1);
    i = j;
  }
  return std::string();
}

} // namespace tetmesher
