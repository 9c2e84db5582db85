// Distances between triangles in floating point, for reporting only (how close two input
// triangles come, in a message); no topological decision is made from them.
#pragma once

namespace tetmesher
{
namespace geometry
{

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
