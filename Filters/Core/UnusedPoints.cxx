#include "UnusedPoints.h"

#include "Predicates.h"
#include "TriangleBoxGrid.h"

#include <algorithm>

namespace tetmesher
{
namespace
{

bool sameCoordinates(const double* a, const double* b)
{
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

// p in the closed triangle abc (not at a corner); abc not degenerate.
bool inClosedTriangle(const double* a, const double* b, const double* c, const double* p)
{
  if (predicates::orient3d(a, b, c, p) != 0)
    return false;
  if (sameCoordinates(p, a) || sameCoordinates(p, b) || sameCoordinates(p, c))
    return false;
  // Coplanar: containment is that of the projection on a plane where abc keeps its area.
  for (int drop = 0; drop < 3; ++drop)
  {
    const int turn = predicates::orient2d(a, b, c, drop);
    if (turn == 0)
      continue;
    return predicates::orient2d(a, b, p, drop) * turn >= 0 &&
      predicates::orient2d(b, c, p, drop) * turn >= 0 &&
      predicates::orient2d(c, a, p, drop) * turn >= 0;
  }
  return false; // a degenerate triangle holds no point here (the diagnosis names it)
}

} // namespace

std::vector<UnusedPointOnSurface> unusedPointsOnSurface(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount)
{
  std::vector<UnusedPointOnSurface> found;
  if (pointCount <= 0 || triangleCount <= 0)
    return found;
  auto valid = [&](std::int32_t t)
  {
    const std::int32_t* v = triangles + 3 * static_cast<std::size_t>(t);
    return v[0] >= 0 && v[1] >= 0 && v[2] >= 0 && v[0] < pointCount && v[1] < pointCount &&
      v[2] < pointCount;
  };
  std::vector<char> used(static_cast<std::size_t>(pointCount), 0);
  for (std::int32_t t = 0; t < triangleCount; ++t)
    if (valid(t))
      for (int k = 0; k < 3; ++k)
        used[static_cast<std::size_t>(triangles[3 * static_cast<std::size_t>(t) + k])] = 1;
  if (std::find(used.begin(), used.end(), 0) == used.end())
    return found;

  auto point = [&](std::int32_t v) { return points + 3 * static_cast<std::size_t>(v); };
  std::vector<TriangleBoxGrid::Box> boxes(static_cast<std::size_t>(triangleCount));
  for (std::int32_t t = 0; t < triangleCount; ++t)
  {
    TriangleBoxGrid::Box& box = boxes[static_cast<std::size_t>(t)];
    if (!valid(t))
    {
      box = { 0, 0, 0, 0, 0, 0 }; // never matched below: its ids are checked first
      continue;
    }
    const std::int32_t* v = triangles + 3 * static_cast<std::size_t>(t);
    for (int k = 0; k < 3; ++k)
    {
      box[k] = std::min({ point(v[0])[k], point(v[1])[k], point(v[2])[k] });
      box[k + 3] = std::max({ point(v[0])[k], point(v[1])[k], point(v[2])[k] });
    }
  }
  const TriangleBoxGrid grid(boxes);
  std::vector<std::int32_t> near;
  for (std::int32_t p = 0; p < pointCount; ++p)
  {
    if (used[static_cast<std::size_t>(p)])
      continue;
    const double* x = point(p);
    grid.near({ x[0], x[1], x[2], x[0], x[1], x[2] }, 0.0, near);
    for (std::int32_t t : near)
    {
      if (!valid(t))
        continue;
      const std::int32_t* v = triangles + 3 * static_cast<std::size_t>(t);
      if (inClosedTriangle(point(v[0]), point(v[1]), point(v[2]), x))
      {
        found.push_back({ p, t });
        break;
      }
    }
  }
  return found;
}

} // namespace tetmesher
