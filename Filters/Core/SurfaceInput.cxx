#include "SurfaceInput.h"

#include "Predicates.h"
#include "RadixSort.h"

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
  SurfaceInput& out)
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
  // Duplicates among the triangles before it (sorted vertex triples, sorted), reported as
  // the triangle-by-triangle scan would: at the first triangle repeating an earlier one.
  {
    std::vector<std::array<VertexId, 4>> keyed(out.triangles.size());
    for (std::size_t t = 0; t < out.triangles.size(); ++t)
    {
      const auto& v = out.triangles[t];
      const auto k = sortedTriangle(v[0], v[1], v[2]);
      keyed[t] = { k[0], k[1], k[2], static_cast<VertexId>(t) };
    }
    std::sort(keyed.begin(), keyed.end());
    std::int32_t first = -1, repeat = firstBad;
    for (std::size_t i = 1; i < keyed.size(); ++i)
      if (std::equal(keyed[i].begin(), keyed[i].begin() + 3, keyed[i - 1].begin()) &&
        keyed[i][3] < repeat)
      {
        // The earliest triangle of this run is the one an earlier scan would have kept.
        std::size_t j = i - 1;
        while (
          j > 0 && std::equal(keyed[j - 1].begin(), keyed[j - 1].begin() + 3, keyed[i].begin()))
          --j;
        first = keyed[j][3];
        repeat = keyed[i][3];
      }
    if (first >= 0)
      return "triangles " + std::to_string(first) + " and " + std::to_string(repeat) +
        " are duplicates";
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
    if (j - i < 2)
    {
      error << "open edge (" << a << "," << b << ") of triangle " << edgeUses[i].second
            << ": the surface must be closed";
      return error.str();
    }
    out.edges.push_back({ a, b });
    out.edgeFirstTriangle.push_back(edgeUses[i].second);
    i = j;
  }
  return std::string();
}

} // namespace tetmesher
