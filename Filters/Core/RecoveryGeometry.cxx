#include "RecoveryGeometry.h"

#include "FilteredPredicates.h"
#include "Predicates.h"

#include <algorithm>

namespace tetmesher
{
namespace geometry
{
namespace
{
using predicates::orient2d;

// orient3d, answering at once for four points on one axis-aligned plane (exactly zero): such
// planar caps are common in CAD input and the general predicate needs its slow exact stage
// to prove a zero.
int orient3d(const double* a, const double* b, const double* c, const double* d)
{
  // A repeated point (callers pass mesh coordinates, so equal vertices share a pointer) is an
  // exact zero that the floating-point filter cannot certify.
  if (a == b || a == c || a == d || b == c || b == d || c == d)
    return 0;
  for (int k = 0; k < 3; ++k)
  {
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k])
      return 0;
  }
  return predicates::orient3dFiltered(a, b, c, d);
}

// A coordinate axis whose projection keeps the triangle abc non-degenerate, or -1 when a, b, c
// are collinear.
int projectionAxis(const double* a, const double* b, const double* c)
{
  for (int axis = 2; axis >= 0; --axis)
  {
    if (orient2d(a, b, c, axis) != 0)
      return axis;
  }
  return -1;
}

bool properCross2D(const double* a, const double* b, const double* u, const double* v, int axis)
{
  return orient2d(a, b, u, axis) * orient2d(a, b, v, axis) < 0 &&
    orient2d(u, v, a, axis) * orient2d(u, v, b, axis) < 0;
}

bool strictlyInside2D(const double* x, const double* p, const double* q, const double* r, int axis)
{
  int s = orient2d(p, q, r, axis);
  return orient2d(p, q, x, axis) == s && orient2d(q, r, x, axis) == s &&
    orient2d(r, p, x, axis) == s;
}
} // namespace

bool segmentMeetsTriangle(const double* a,
  const double* b,
  const double* p,
  const double* q,
  const double* r)
{
  int sa = orient3d(p, q, r, a);
  int sb = orient3d(p, q, r, b);
  if (sa * sb > 0)
    return false;
  if (sa == 0 && sb == 0)
  {
    int axis = projectionAxis(p, q, r);
    if (axis < 0)
      return false;
    if (strictlyInside2D(a, p, q, r, axis) || strictlyInside2D(b, p, q, r, axis))
      return true;
    return properCross2D(a, b, p, q, axis) || properCross2D(a, b, q, r, axis) ||
      properCross2D(a, b, r, p, axis);
  }
  if (sa == 0 || sb == 0)
    return false; // touches the plane only at an end point, which the open segment excludes
  int s1 = orient3d(a, b, p, q);
  int s2 = orient3d(a, b, q, r);
  int s3 = orient3d(a, b, r, p);
  return s1 != 0 && s1 == s2 && s2 == s3;
}

bool segmentsCross(const double* a, const double* b, const double* p, const double* q)
{
  if (orient3d(a, b, p, q) != 0)
    return false;
  int axis = projectionAxis(a, b, p);
  if (axis < 0)
    axis = projectionAxis(a, b, q);
  if (axis < 0)
    return false; // collinear: overlap would put a vertex inside an edge
  return properCross2D(a, b, p, q, axis);
}

bool simplexMeetsTetInterior(const double* const* points, int count, const double* const t[4])
{
  if (count == 2)
  {
    // A segment from a vertex of the tet (the usual case: the pipe of a missing edge grows
    // from the star of its end point) enters the interior iff its other end is strictly
    // inside the three faces through that vertex: along the segment their signs are those
    // of the other end scaled by the parameter, and the opposite face is positive near the
    // vertex. Vertices are compared by pointer, as the mesh passes them.
    for (int end = 0; end < 2; ++end)
    {
      for (int i = 0; i < 4; ++i)
      {
        if (points[end] != t[i])
          continue;
        const double* other = points[1 - end];
        for (int f = 0; f < 4; ++f)
        {
          if (f == i)
            continue;
          // Face f (opposite t[f]) replaced by `other` keeps the tet's positive orientation
          // exactly when `other` is on t[f]'s side of it.
          const double* q[4] = { t[0], t[1], t[2], t[3] };
          q[f] = other;
          if (orient3d(q[0], q[1], q[2], q[3]) <= 0)
            return false;
        }
        return true;
      }
    }
  }
  // Disjoint bounding boxes separate the sets (exact comparisons).
  for (int k = 0; k < 3; ++k)
  {
    double sMin = points[0][k], sMax = points[0][k];
    for (int i = 1; i < count; ++i)
    {
      sMin = std::min(sMin, points[i][k]);
      sMax = std::max(sMax, points[i][k]);
    }
    double tMin = std::min({ t[0][k], t[1][k], t[2][k], t[3][k] });
    double tMax = std::max({ t[0][k], t[1][k], t[2][k], t[3][k] });
    if (sMax <= tMin || sMin >= tMax)
      return false;
  }
  // Two convex sets are disjoint iff a plane separates them (closed sides); such a plane can
  // be rotated until it passes through three of the points. Try them all, the tet's own
  // faces first (they separate most often).
  const double* all[7] = { t[0], t[1], t[2], t[3] };
  const int n = 4 + count;
  for (int i = 0; i < count; ++i)
    all[4 + i] = points[i];
  for (int pass = 0; pass < 2; ++pass)
  {
    for (int i = 0; i < n; ++i)
    {
      for (int j = i + 1; j < n; ++j)
      {
        for (int k = j + 1; k < n; ++k)
        {
          if ((k < 4) != (pass == 0))
            continue;
          int simplexSide = 0;
          int tetSide = 0;
          bool separates = true;
          bool degenerate = true;
          for (int m = 0; m < n && separates; ++m)
          {
            if (m == i || m == j || m == k)
              continue; // on the plane by construction
            int s = orient3d(all[i], all[j], all[k], all[m]);
            if (s == 0)
              continue;
            degenerate = false;
            int& side = m >= 4 ? simplexSide : tetSide;
            if (side == 0)
              side = s;
            else if (side != s)
              separates = false;
          }
          if (degenerate || !separates)
            continue;
          if (simplexSide == 0 || tetSide == 0 || simplexSide != tetSide)
            return false;
        }
      }
    }
  }
  return true;
}

bool pointOnTriangle(const double* x, const double* p, const double* q, const double* r)
{
  if (orient3d(p, q, r, x) != 0)
    return false;
  int axis = projectionAxis(p, q, r);
  if (axis < 0)
    return false;
  int s = orient2d(p, q, r, axis);
  return orient2d(p, q, x, axis) != -s && orient2d(q, r, x, axis) != -s &&
    orient2d(r, p, x, axis) != -s;
}

bool pointInsideTet(const double* x, const double* const t[4])
{
  return orient3d(t[0], t[1], t[2], x) > 0 && orient3d(t[0], t[3], t[1], x) > 0 &&
    orient3d(t[1], t[3], t[2], x) > 0 && orient3d(t[0], t[2], t[3], x) > 0;
}

} // namespace geometry
} // namespace tetmesher
