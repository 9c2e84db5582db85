// Points that no input triangle uses but that lie on the surface (in a triangle or on an edge,
// decided exactly). Such a point cannot be a mesh vertex without splitting the triangle, which
// the exact boundary forbids, and inserted it would leave the triangle unrecoverable; so it is
// left out of the mesh (a warning names it). Surfaces from VTK pipelines often keep the points
// that a decimation or a clip stopped using, and on a planar part they lie on its triangles.
// Other unused points are inserted (as TetGen does): inside the volume they become vertices.
#pragma once

#include <cstdint>
#include <vector>

namespace tetmesher
{

struct UnusedPointOnSurface
{
  std::int32_t point;
  std::int32_t triangle; // the lowest-numbered input triangle that holds it
};

// In increasing point order. A point equal to a triangle's corner is not listed: that is a
// duplicate point (an error the diagnosis names). Triangles with ids outside 0..pointCount-1
// are skipped. Costs one pass over the triangles when no point is unused.
std::vector<UnusedPointOnSurface> unusedPointsOnSurface(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount);

} // namespace tetmesher
