// Exact intersection tests between segments and triangles in 3D, built only on the exact
// predicates (orient3d, orient2d). No epsilon: every answer is exact for finite double input.
// Used by the input diagnosis (self-intersections) and available to the other stages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tetmesher
{

// An axis (0,1,2) such that dropping it keeps triangle (a,b,c) non-degenerate in 2D, preferring
// the dominant axis of its normal; -1 when the triangle is degenerate (its three points are
// collinear, exactly).
int triangleProjectionAxis(const double* a, const double* b, const double* c);

// True when the three points are exactly collinear (or coincide): zero-area triangle.
inline bool isTriangleDegenerate(const double* a, const double* b, const double* c)
{
  return triangleProjectionAxis(a, b, c) < 0;
}

// True when the closed segment pq and the closed, non-degenerate triangle abc share a point.
bool segmentIntersectsTriangle(const double* p,
  const double* q,
  const double* a,
  const double* b,
  const double* c);

// True when two non-degenerate triangles share a point that is not a vertex or edge they share
// by id. `p[i]` are the coordinates of vertex ids `pi[i]`, same for q/qi; equal ids mean the same
// vertex, different ids must mean different coordinates (merge coincident points beforehand).
// Two triangles with the same three ids are reported as not intersecting (that is a duplicate
// triangle, a different defect).
bool trianglesIntersectImproperly(const double* const p[3],
  const std::int32_t pi[3],
  const double* const q[3],
  const std::int32_t qi[3]);

// Orders the half-planes bounded by the line uv that contain the points w[0..n-1] (none on the
// line) by increasing angle about the axis u->v, counterclockwise for the right-hand rule,
// starting at the half-plane of w[0]; returns indices into w. Exact. Points on one half-plane
// keep their relative order. The triangle (u,v,w[i]) has its normal pointing towards the
// next half-plane counterclockwise.
std::vector<std::size_t> sortAroundEdge(const double* u,
  const double* v,
  const std::vector<const double*>& w);

} // namespace tetmesher
