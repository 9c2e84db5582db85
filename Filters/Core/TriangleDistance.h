// Distances between points, boxes and triangles in floating point, for reporting (how close two
// input triangles come, in a message) and for sizes (the refinement's boundary size limits); no
// topological decision is made from them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tetmesher
{
namespace geometry
{

// Distance from x to the axis-aligned box (min x, y, z, max x, y, z); 0 inside. Inline: the
// boundary size floor's and ceiling's tree searches call it for every node they look at (a
// sixth of a femur's refinement as a call).
inline double pointBoxDistance(const double* x, const double* box)
{
  double d2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double d = std::max({ box[a] - x[a], x[a] - box[3 + a], 0.0 });
    d2 += d * d;
  }
  return std::sqrt(d2);
}

// The triangle whose 3 corners are points[ids[0..2]] (xyz per point): their coordinates in
// `corner` (9 doubles) and their bounding box in `box` (min x, y, z, max x, y, z).
void gatherTriangle(const double* points, const std::int32_t* ids, double* corner, double* box);

// Squared distance from x to the closed triangle (a,b,c); for a degenerate triangle, to its
// longest edge.
double pointTriangleDistanceSquared(const double* x,
  const double* a,
  const double* b,
  const double* c);

// Squared distance between the closed segments (p,q) and (r,s).
double segmentDistanceSquared(const double* p, const double* q, const double* r, const double* s);

// Squared distance between two closed triangles that do not intersect: the least over the
// vertex-triangle and edge-edge pairs (for intersecting triangles the result is an upper bound
// of 0's neighbourhood, not 0).
double triangleDistanceSquared(const double* const t[3], const double* const u[3]);

} // namespace geometry
} // namespace tetmesher
