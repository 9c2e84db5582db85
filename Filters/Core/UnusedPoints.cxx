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

// p in the closed triangle abc; abc not degenerate.
bool inClosedTriangle(const double* a, const double* b, const double* c, const double* p)
{
  if (predicates::orient3d(a, b, c, p) != 0)
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

std::vector<LeftOutPoint> unusedPointsLeftOut(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount)
{
  std::vector<LeftOutPoint> found;
  if (pointCount <= 0)
    return found;
  auto point = [&](std::int32_t v) { return points + 3 * static_cast<std::size_t>(v); };
  auto decidable = [&](std::int32_t v)
  {
    const double* x = point(v);
    return predicates::inExactRange(x[0]) && predicates::inExactRange(x[1]) &&
      predicates::inExactRange(x[2]);
  };
  auto corners = [&](std::int32_t t) { return triangles + 3 * static_cast<std::size_t>(t); };
  auto validIds = [&](const std::int32_t* v)
  {
    return v[0] >= 0 && v[1] >= 0 && v[2] >= 0 && v[0] < pointCount && v[1] < pointCount &&
      v[2] < pointCount;
  };
  // The one pass every run pays (most surfaces use every point): the rest only when one is not.
  std::vector<char> used(static_cast<std::size_t>(pointCount), 0);
  for (std::int32_t t = 0; t < triangleCount; ++t)
  {
    const std::int32_t* v = corners(t);
    if (validIds(v))
      for (int k = 0; k < 3; ++k)
        used[static_cast<std::size_t>(v[k])] = 1;
  }
  std::vector<std::int32_t> unused;
  for (std::int32_t p = 0; p < pointCount; ++p)
    if (!used[static_cast<std::size_t>(p)] && decidable(p))
      unused.push_back(p);
  if (unused.empty())
    return found;

  // On the surface: the triangles near each unused point, from a grid of the usable ones'
  // boxes (an unusable one's box could stretch the grid across the model).
  std::vector<std::int32_t> usableIds;
  std::vector<TriangleBoxGrid::Box> boxes;
  for (std::int32_t t = 0; t < triangleCount; ++t)
  {
    const std::int32_t* v = corners(t);
    if (!validIds(v) || !decidable(v[0]) || !decidable(v[1]) || !decidable(v[2]))
      continue;
    TriangleBoxGrid::Box box;
    for (int k = 0; k < 3; ++k)
    {
      box[k] = std::min({ point(v[0])[k], point(v[1])[k], point(v[2])[k] });
      box[k + 3] = std::max({ point(v[0])[k], point(v[1])[k], point(v[2])[k] });
    }
    usableIds.push_back(t);
    boxes.push_back(box);
  }
  std::vector<char> onSurface(unused.size(), 0);
  if (!boxes.empty())
  {
    const TriangleBoxGrid grid(boxes);
    std::vector<std::int32_t> near;
    for (std::size_t i = 0; i < unused.size(); ++i)
    {
      const double* x = point(unused[i]);
      grid.near({ x[0], x[1], x[2], x[0], x[1], x[2] }, 0.0, near);
      for (std::int32_t k : near) // increasing, so the lowest triangle first
      {
        const std::int32_t t = usableIds[static_cast<std::size_t>(k)];
        const std::int32_t* v = corners(t);
        if (!inClosedTriangle(point(v[0]), point(v[1]), point(v[2]), x))
          continue;
        std::int32_t equalTo = -1;
        for (int k = 0; k < 3; ++k)
          if (sameCoordinates(point(v[k]), x))
            equalTo = v[k];
        found.push_back({ unused[i], t, equalTo });
        onSurface[i] = 1;
        break;
      }
    }
  }
  // Equal unused points off the surface: the lowest id stands for its group.
  std::vector<std::int32_t> apart;
  for (std::size_t i = 0; i < unused.size(); ++i)
    if (!onSurface[i])
      apart.push_back(unused[i]);
  auto less = [&](std::int32_t a, std::int32_t b)
  {
    const double *p = point(a), *q = point(b);
    for (int k = 0; k < 3; ++k)
      if (p[k] != q[k])
        return p[k] < q[k];
    return a < b;
  };
  std::sort(apart.begin(), apart.end(), less);
  for (std::size_t i = 1; i < apart.size(); ++i)
  {
    std::size_t first = i - 1;
    while (i < apart.size() && sameCoordinates(point(apart[first]), point(apart[i])))
      found.push_back({ apart[i++], -1, apart[first] });
  }
  std::sort(found.begin(),
    found.end(),
    [](const LeftOutPoint& a, const LeftOutPoint& b) { return a.point < b.point; });
  return found;
}

} // namespace tetmesher
