#include "RecoveryGeometry.h"

#include "FilteredPredicates.h"
#include "Predicates.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstdint>
#include <iterator>
#include <vector>

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

int orientWithVertexReplaced(const double* const t[4], int f, const double* x)
{
  const double* q[4] = { t[0], t[1], t[2], t[3] };
  q[f] = x;
  return orient3d(q[0], q[1], q[2], q[3]);
}

bool segmentFromVertexMissesTet(const double* const t[4], int i, const double* b)
{
  for (int f = 0; f < 4; ++f)
  {
    if (f != i && orientWithVertexReplaced(t, f, b) < 0)
      return true;
  }
  return false;
}

namespace
{
// The open segment (t[i], b) meets the open tet iff b is strictly inside the three faces
// through t[i]: along the segment their signs are those of b scaled by the parameter, and the
// opposite face is positive near t[i].
bool segmentFromVertexMeetsTet(const double* const t[4], int i, const double* b)
{
  for (int f = 0; f < 4; ++f)
  {
    if (f != i && orientWithVertexReplaced(t, f, b) <= 0)
      return false;
  }
  return true;
}

// The open segment ab meets the open tet (any position): the point (1-s) a + s b is inside
// face f iff (1-s) A_f + s B_f > 0, with A_f, B_f the signed distances of a and b. A face
// with A_f, B_f <= 0 excludes the segment; A_f < 0 < B_f bounds s from below by the crossing
// with plane f, A_f > 0 > B_f from above; the others do not constrain. A lower bound from f
// is below an upper one from g iff A_g B_f - A_f B_g > 0, which is (n_g x n_f).((a-e0) x
// (b-e0)) (Binet-Cauchy; e0, e1: the edge shared by faces f and g, along n_g x n_f): the sign
// of -det(t[f]-e0, t[g]-e0, e1-e0) det(a-e0, b-e0, e1-e0) (calibrated on a = t[f], b = t[g],
// where the expression is -A_f B_g < 0). All signs exact.
bool segmentMeetsTet(const double* const t[4], const double* a, const double* b)
{
  int lower[4], upper[4];
  int lowerCount = 0, upperCount = 0;
  for (int f = 0; f < 4; ++f)
  {
    const int sa = orientWithVertexReplaced(t, f, a), sb = orientWithVertexReplaced(t, f, b);
    if (sa <= 0 && sb <= 0)
      return false;
    if (sa < 0 && sb > 0)
      lower[lowerCount++] = f;
    else if (sa > 0 && sb < 0)
      upper[upperCount++] = f;
  }
  for (int l = 0; l < lowerCount; ++l)
  {
    for (int u = 0; u < upperCount; ++u)
    {
      const int f = lower[l], g = upper[u];
      int edge[2], n = 0;
      for (int k = 0; k < 4; ++k)
      {
        if (k != f && k != g)
          edge[n++] = k;
      }
      const double *e0 = t[edge[0]], *e1 = t[edge[1]];
      if (orient3d(t[f], t[g], e1, e0) * orient3d(a, b, e1, e0) >= 0)
        return false;
    }
  }
  return true;
}

// The open triangle (a = t[i], b, c) meets the open tet iff its open wedge at a meets the open
// cone of the tet at a (both sets are those cones near a, and lie inside them). A point
// a + r (b - a) + (c - a), r > 0, is inside face f iff r A_f + B_f > 0 with A_f = n_f.(b-a),
// B_f = n_f.(c-a): a constraint r > -B_f/A_f (A_f > 0 > B_f), r < -B_f/A_f (A_f < 0 < B_f),
// none (both >= 0, one > 0), or no r at all (both <= 0). A lower bound from f is below an
// upper one from g iff A_f B_g - A_g B_f > 0, and that is (n_f x n_g).((b-a) x (c-a)) by
// Binet-Cauchy, with n_f x n_g along the edge (a, t[m]) shared by the two faces: its sign is
// that of det(t[f]-a, t[g]-a, t[m]-a) det(b-a, c-a, t[m]-a) (the first factor calibrates the
// direction: for b = t[f], c = t[g] the expression is A_f B_g > 0). All signs exact.
bool triangleFromVertexMeetsTet(const double* const t[4], int i, const double* b, const double* c)
{
  int lower[3], upper[3];
  int lowerCount = 0, upperCount = 0;
  for (int f = 0; f < 4; ++f)
  {
    if (f == i)
      continue;
    const int sb = orientWithVertexReplaced(t, f, b), sc = orientWithVertexReplaced(t, f, c);
    if (sb <= 0 && sc <= 0)
      return false;
    if (sb > 0 && sc < 0)
      lower[lowerCount++] = f;
    else if (sb < 0 && sc > 0)
      upper[upperCount++] = f;
  }
  const double* a = t[i];
  for (int l = 0; l < lowerCount; ++l)
  {
    for (int u = 0; u < upperCount; ++u)
    {
      const int f = lower[l], g = upper[u], m = 6 - i - f - g;
      const int calibration = orient3d(t[f], t[g], t[m], a);
      const int side = orient3d(b, c, t[m], a);
      if (calibration * side <= 0)
        return false;
    }
  }
  return true;
}
} // namespace

bool simplexMeetsTetInterior(const double* const* points, int count, const double* const t[4])
{
  // A simplex with a vertex of the tet (the usual case: a missing item's pipe grows from the
  // star of its first vertex) is decided at that vertex by a few orientations, any segment by
  // its crossings with the face planes. Vertices are compared by pointer, as the mesh passes
  // them.
  for (int end = 0; end < count; ++end)
  {
    for (int i = 0; i < 4; ++i)
    {
      if (points[end] != t[i])
        continue;
      if (count == 2)
        return segmentFromVertexMeetsTet(t, i, points[1 - end]);
      return triangleFromVertexMeetsTet(t, i, points[(end + 1) % 3], points[(end + 2) % 3]);
    }
  }
  if (count == 2)
    return segmentMeetsTet(t, points[0], points[1]);
  return simplexMeetsTetInteriorBySeparation(points, count, t);
}

namespace
{
// The planes simplexMeetsTetInteriorBySeparation tries for n = 4 + count points (tet
// vertices first), in its order: the tet's faces, then the planes through a point of the
// simplex, each through points i < j < k, with the other points m in increasing order and
// which 4-point set orient3d(i, j, k, m) is, up to the parity of sorting it.
struct SeparationPlanes
{
  struct Point
  {
    std::uint8_t subset; // index into subsets
    bool odd;            // orient3d(i, j, k, m) is minus the subset's orientation
    bool simplex;        // m is a point of the simplex
  };
  struct Plane
  {
    int count = 0;
    Point others[4];
  };
  std::vector<Plane> planes;
  std::vector<std::array<std::uint8_t, 4>> subsets; // increasing indices

  explicit SeparationPlanes(int n)
  {
    std::uint8_t subsetOfMask[128]; // by the set's bitmask; 0xff: none yet
    std::fill(std::begin(subsetOfMask), std::end(subsetOfMask), std::uint8_t(0xff));
    for (int pass = 0; pass < 2; ++pass)
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
          for (int k = j + 1; k < n; ++k)
          {
            if ((k < 4) != (pass == 0))
              continue;
            Plane plane;
            for (int m = 0; m < n; ++m)
            {
              if (m == i || m == j || m == k)
                continue; // on the plane by construction
              const int mask = (1 << i) | (1 << j) | (1 << k) | (1 << m);
              if (subsetOfMask[mask] == 0xff)
              {
                subsetOfMask[mask] = static_cast<std::uint8_t>(subsets.size());
                std::array<std::uint8_t, 4> sorted{};
                for (int b = 0, e = 0; b < n; ++b)
                  if (mask & (1 << b))
                    sorted[e++] = static_cast<std::uint8_t>(b);
                subsets.push_back(sorted);
              }
              // m moves past the indices above it: one transposition each.
              plane.others[plane.count++] = {
                subsetOfMask[mask], ((i > m) + (j > m) + (k > m)) % 2 == 1, m >= 4
              };
            }
            planes.push_back(plane);
          }
  }
};

// The table for n = 5, 6 or 7 points (a point, a segment or a triangle against the tet).
const SeparationPlanes& separationPlanes(int n)
{
  assert(n >= 5 && n <= 7);
  static const SeparationPlanes tables[3] = {
    SeparationPlanes(5), SeparationPlanes(6), SeparationPlanes(7)
  };
  return tables[n - 5];
}
} // namespace

bool simplexMeetsTetInteriorBySeparation(const double* const* points,
  int count,
  const double* const t[4])
{
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
  // The planes test up to 140 orientations but only 35 distinct point sets: each sign is
  // computed once (2: not yet), in the set's increasing index order. The signs are exact,
  // so a permutation only multiplies them by its parity.
  const SeparationPlanes& planes = separationPlanes(n);
  signed char signs[35];
  std::fill(std::begin(signs), std::end(signs), static_cast<signed char>(2));
  for (const SeparationPlanes::Plane& plane : planes.planes)
  {
    int simplexSide = 0;
    int tetSide = 0;
    bool separates = true;
    bool degenerate = true;
    for (int e = 0; e < plane.count && separates; ++e)
    {
      const SeparationPlanes::Point& point = plane.others[e];
      signed char& sign = signs[point.subset];
      if (sign == 2)
      {
        const std::uint8_t* v = planes.subsets[point.subset].data();
        sign = static_cast<signed char>(orient3d(all[v[0]], all[v[1]], all[v[2]], all[v[3]]));
      }
      const int s = point.odd ? -sign : sign;
      if (s == 0)
        continue;
      degenerate = false;
      int& side = point.simplex ? simplexSide : tetSide;
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
