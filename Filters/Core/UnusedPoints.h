// Points that no input triangle uses and that the mesh leaves out:
// - those on the surface (in a triangle, on an edge or at a corner, decided exactly): such a
//   point cannot be a mesh vertex without splitting a triangle, which the exact boundary
//   forbids, and inserted it would leave the triangle unrecoverable;
// - those equal to an earlier unused point (one vertex stands for them).
// Surfaces from VTK pipelines often keep the points that a decimation or a clip stopped using,
// and on a planar part they lie on its triangles. Other unused points are inserted (as TetGen
// does): inside the volume they become vertices. A warning names the ones left out.
#pragma once

#include <cstdint>
#include <vector>

namespace tetmesher
{

struct LeftOutPoint
{
  std::int32_t point;
  std::int32_t triangle; // the lowest-numbered input triangle that holds it, or -1
  std::int32_t equalTo;  // the point it equals (a triangle corner or an unused point), or -1
};

// In increasing point order. Points with a coordinate that is not finite or not in the exact
// range, and triangles with such a corner or with ids outside 0..pointCount-1, are skipped
// (the diagnosis names them). Costs one pass over the triangles when no point is unused.
std::vector<LeftOutPoint> unusedPointsLeftOut(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount);

} // namespace tetmesher
