#include "TriangleIntersection.h"

#include "Predicates.h"

#include <algorithm>
#include <cmath>

namespace tetmesher
{

namespace
{

// The exact predicates are fast when the answer is not zero (the floating-point filter
// decides) and slow when it is exactly zero (full expansion arithmetic). Surfaces from CAD and
// from extrusions are full of exactly coplanar points in axis-aligned planes: recognise those
// zeros directly. Both shortcuts are exact.
int orient3d(const double* a, const double* b, const double* c, const double* d)
{
  for (int k = 0; k < 3; ++k)
  {
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k])
      return 0; // all four in the plane x_k = const
  }
  return predicates::orient3d(a, b, c, d);
}

int orient2d(const double* a, const double* b, const double* c, int dropAxis)
{
  for (int k = 0; k < 3; ++k)
  {
    if (k != dropAxis && a[k] == b[k] && a[k] == c[k])
      return 0; // all three on a line x_k = const of the projection plane
  }
  return predicates::orient2d(a, b, c, dropAxis);
}

// Closed 2D segments pq and rs (projection dropping `axis`) share a point.
bool segmentsIntersect2D(const double* p,
  const double* q,
  const double* r,
  const double* s,
  int axis)
{
  const int o1 = orient2d(p, q, r, axis);
  const int o2 = orient2d(p, q, s, axis);
  if (o1 == 0 && o2 == 0)
  {
    // Collinear: for collinear segments, overlapping boxes on both kept axes is overlap.
    for (int k = 0; k < 3; ++k)
    {
      if (k == axis)
        continue;
      if (std::max(p[k], q[k]) < std::min(r[k], s[k]) ||
        std::max(r[k], s[k]) < std::min(p[k], q[k]))
        return false;
    }
    return true;
  }
  if (o1 * o2 > 0)
    return false;
  const int o3 = orient2d(r, s, p, axis);
  const int o4 = orient2d(r, s, q, axis);
  return o3 * o4 <= 0;
}

// Point p in the closed 2D triangle abc (non-degenerate in this projection).
bool pointInTriangle2D(const double* p, const double* a, const double* b, const double* c, int axis)
{
  const int o = orient2d(a, b, c, axis);
  return orient2d(a, b, p, axis) * o >= 0 && orient2d(b, c, p, axis) * o >= 0 &&
    orient2d(c, a, p, axis) * o >= 0;
}

// Segment pq lying in the plane of triangle abc: do they share a point?
bool coplanarSegmentIntersectsTriangle(const double* p,
  const double* q,
  const double* a,
  const double* b,
  const double* c)
{
  const int axis = triangleProjectionAxis(a, b, c);
  if (axis < 0)
    return false;
  return pointInTriangle2D(p, a, b, c, axis) || pointInTriangle2D(q, a, b, c, axis) ||
    segmentsIntersect2D(p, q, a, b, axis) || segmentsIntersect2D(p, q, b, c, axis) ||
    segmentsIntersect2D(p, q, c, a, axis);
}

// Triangle (v,a,b) and the segment v-w (w != v) share the vertex v. Does the segment contain
// points of the triangle other than v? Only possible when w lies in the triangle's plane, and
// then exactly when the direction v->w lies in the closed angle of the triangle at v.
bool segmentFromSharedVertexEntersTriangle(const double* v,
  const double* w,
  const double* a,
  const double* b)
{
  if (orient3d(v, a, b, w) != 0)
    return false;
  const int axis = triangleProjectionAxis(v, a, b);
  if (axis < 0)
    return false;
  const int o = orient2d(v, a, b, axis);
  return orient2d(v, a, w, axis) * o >= 0 && orient2d(v, w, b, axis) * o >= 0;
}

// All three points strictly on one side of the plane of triangle t.
bool strictlyOneSide(const double* const t[3], const double* x, const double* y, const double* z)
{
  const int sx = orient3d(t[0], t[1], t[2], x);
  if (sx == 0)
    return false;
  const int sy = orient3d(t[0], t[1], t[2], y);
  if (sy != sx)
    return false;
  if (z == nullptr)
    return true;
  return orient3d(t[0], t[1], t[2], z) == sx;
}

// Closed coplanar triangles p and q, non-degenerate in the projection dropping `axis`, where
// their orientations are op and oq (not 0): do they share a point? They are disjoint exactly
// when an edge line of one has the whole other triangle strictly on its outer side
// (separating axes of convex polygons).
bool coplanarTrianglesMeet(const double* const p[3],
  int op,
  const double* const q[3],
  int oq,
  int axis)
{
  auto separates = [axis](const double* const t[3], int o, const double* const other[3])
  {
    for (int i = 0; i < 3; ++i)
    {
      const double* a = t[i];
      const double* b = t[(i + 1) % 3];
      if (orient2d(a, b, other[0], axis) * o < 0 && orient2d(a, b, other[1], axis) * o < 0 &&
        orient2d(a, b, other[2], axis) * o < 0)
        return true;
    }
    return false;
  };
  return !separates(p, op, q) && !separates(q, oq, p);
}

// The direction v->w lies in the closed angle of the (non-degenerate, projected) triangle
// (v,a,b) at v, whose orientation is o.
bool rayInAngle(const double* v, const double* w, const double* a, const double* b, int o, int axis)
{
  return orient2d(v, a, w, axis) * o >= 0 && orient2d(v, w, b, axis) * o >= 0;
}

} // namespace

int triangleProjectionAxis(const double* a, const double* b, const double* c)
{
  // The dominant normal axis is tried first (best conditioned), but any axis whose exact 2D
  // orientation is non-zero gives a faithful projection of the triangle's plane.
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double n[3] = {
    std::fabs(uy * vz - uz * vy), std::fabs(uz * vx - ux * vz), std::fabs(ux * vy - uy * vx)
  };
  int order[3] = { 0, 1, 2 };
  std::sort(order, order + 3, [&](int i, int j) { return n[i] > n[j]; });
  for (int axis : order)
  {
    if (orient2d(a, b, c, axis) != 0)
      return axis;
  }
  return -1;
}

bool segmentIntersectsTriangle(const double* p,
  const double* q,
  const double* a,
  const double* b,
  const double* c)
{
  const int op = orient3d(a, b, c, p);
  const int oq = orient3d(a, b, c, q);
  if (op * oq > 0)
    return false;
  if (op == 0 && oq == 0)
    return coplanarSegmentIntersectsTriangle(p, q, a, b, c);
  // The segment meets the plane in one point; it lies in the closed triangle iff the line pq
  // sees the three edges with no two strictly opposite orientations.
  const int s1 = orient3d(p, q, a, b);
  const int s2 = orient3d(p, q, b, c);
  const int s3 = orient3d(p, q, c, a);
  const bool pos = s1 > 0 || s2 > 0 || s3 > 0;
  const bool neg = s1 < 0 || s2 < 0 || s3 < 0;
  return !(pos && neg);
}

bool trianglesIntersectImproperly(const double* const p[3],
  const std::int32_t pi[3],
  const double* const q[3],
  const std::int32_t qi[3])
{
  int shared = 0;
  bool pShared[3] = { false, false, false };
  bool qShared[3] = { false, false, false };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      if (pi[i] == qi[j] && !qShared[j])
      {
        ++shared;
        pShared[i] = true;
        qShared[j] = true;
        break;
      }
    }
  }
  if (shared == 3)
    return false;

  if (shared == 2)
  {
    // Sharing an edge uv: they overlap beyond it only when coplanar with the third vertices on
    // the same side of uv.
    int ip = 0, iq = 0;
    while (pShared[ip])
      ++ip;
    while (qShared[iq])
      ++iq;
    const double* u = p[(ip + 1) % 3];
    const double* v = p[(ip + 2) % 3];
    const double* w1 = p[ip];
    const double* w2 = q[iq];
    if (orient3d(u, v, w1, w2) != 0)
      return false;
    const int axis = triangleProjectionAxis(u, v, w1);
    if (axis < 0)
      return false;
    return orient2d(u, v, w1, axis) * orient2d(u, v, w2, axis) > 0;
  }

  if (shared == 1)
  {
    int ip = 0, iq = 0;
    while (!pShared[ip])
      ++ip;
    while (!qShared[iq])
      ++iq;
    const double* v = p[ip];
    const double* a1 = p[(ip + 1) % 3];
    const double* b1 = p[(ip + 2) % 3];
    const double* a2 = q[(iq + 1) % 3];
    const double* b2 = q[(iq + 2) % 3];
    // If one triangle's other vertices lie strictly on one side of the other's plane, the
    // triangles meet only in v.
    const int sa = orient3d(q[0], q[1], q[2], a1);
    const int sb = orient3d(q[0], q[1], q[2], b1);
    if (sa == 0 && sb == 0)
    {
      // Coplanar (fans on the planar faces of CAD parts: most pairs there). Each triangle
      // lies in its angle at v, so they meet beyond v exactly when the angles share a ray,
      // and then a side of one angle lies in the other.
      const int axis = triangleProjectionAxis(v, a1, b1);
      const int o1 = axis < 0 ? 0 : orient2d(v, a1, b1, axis);
      const int o2 = axis < 0 ? 0 : orient2d(v, a2, b2, axis);
      if (o1 != 0 && o2 != 0)
        return rayInAngle(v, a2, a1, b1, o1, axis) || rayInAngle(v, b2, a1, b1, o1, axis) ||
          rayInAngle(v, a1, a2, b2, o2, axis) || rayInAngle(v, b1, a2, b2, o2, axis);
    }
    if ((sa != 0 && sb == sa) || strictlyOneSide(p, a2, b2, nullptr))
      return false;
    // Otherwise their intersection is a convex set containing v; it has another point iff an
    // edge of one triangle meets the other triangle outside v.
    return segmentIntersectsTriangle(a1, b1, q[0], q[1], q[2]) ||
      segmentIntersectsTriangle(a2, b2, p[0], p[1], p[2]) ||
      segmentFromSharedVertexEntersTriangle(v, a1, a2, b2) ||
      segmentFromSharedVertexEntersTriangle(v, b1, a2, b2) ||
      segmentFromSharedVertexEntersTriangle(v, a2, a1, b1) ||
      segmentFromSharedVertexEntersTriangle(v, b2, a1, b1);
  }

  // No shared vertex: any common point means an intersection, and if there is one, some edge
  // of one triangle meets the other triangle.
  const int s0 = orient3d(q[0], q[1], q[2], p[0]);
  const int s1 = orient3d(q[0], q[1], q[2], p[1]);
  if (s0 == 0 && s1 == 0 && orient3d(q[0], q[1], q[2], p[2]) == 0)
  {
    // Coplanar (neighbouring triangles of a planar face): one separating-axis test in the
    // plane instead of six segment tests.
    const int axis = triangleProjectionAxis(q[0], q[1], q[2]);
    const int op = axis < 0 ? 0 : orient2d(p[0], p[1], p[2], axis);
    if (op != 0)
      return coplanarTrianglesMeet(p, op, q, orient2d(q[0], q[1], q[2], axis), axis);
  }
  if ((s0 != 0 && s1 == s0 && orient3d(q[0], q[1], q[2], p[2]) == s0) ||
    strictlyOneSide(p, q[0], q[1], q[2]))
    return false;
  for (int i = 0; i < 3; ++i)
  {
    if (segmentIntersectsTriangle(p[i], p[(i + 1) % 3], q[0], q[1], q[2]))
      return true;
    if (segmentIntersectsTriangle(q[i], q[(i + 1) % 3], p[0], p[1], p[2]))
      return true;
  }
  return false;
}

std::vector<std::size_t> sortAroundEdge(const double* u,
  const double* v,
  const std::vector<const double*>& w)
{
  std::vector<std::size_t> ring;
  if (w.empty())
    return ring;
  // orient3d(u,v,wi,wj) < 0 iff wj is on the normal side of (u,v,wi), i.e. its angle lies in
  // (angle_i, angle_i + pi). Split at the half-plane of w[0] and its opposite, then sort each
  // open half-turn by that comparison.
  const int axis = triangleProjectionAxis(u, v, w[0]);
  const int side0 = axis < 0 ? 0 : orient2d(u, v, w[0], axis);
  std::vector<std::size_t> group[4]; // angle 0, (0,pi), pi, (pi,2pi)
  for (std::size_t k = 0; k < w.size(); ++k)
  {
    const int o = k == 0 ? 0 : orient3d(u, v, w[0], w[k]);
    if (o < 0)
      group[1].push_back(k);
    else if (o > 0)
      group[3].push_back(k);
    else if (k == 0 || orient2d(u, v, w[k], axis < 0 ? 0 : axis) * side0 > 0)
      group[0].push_back(k);
    else
      group[2].push_back(k);
  }
  auto before = [&](std::size_t a, std::size_t b) { return orient3d(u, v, w[a], w[b]) < 0; };
  std::stable_sort(group[1].begin(), group[1].end(), before);
  std::stable_sort(group[3].begin(), group[3].end(), before);
  for (const auto& g : group)
    ring.insert(ring.end(), g.begin(), g.end());
  return ring;
}

} // namespace tetmesher
