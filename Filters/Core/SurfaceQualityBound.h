// The best quality a mesh that keeps the surface exactly can reach.
//
// Every input triangle F is a face of a tet of the output (the surface is never split), and a
// tet with face F has Q = 2 sqrt(6) r / lmax <= 2 sqrt(6) area(F) / l(F)^2, l(F) being F's
// longest edge. Why: with H the height of the fourth vertex over F's plane, the volume is
// area(F) H / 3; each other face has an edge on F and an area of at least that edge's length
// times H / 2, and those edges (F's perimeter) sum to at least 2 l(F) (triangle inequality),
// so the surface area S is at least l(F) H and the inradius r = 3 V / S at most
// area(F) / l(F); the tet's longest edge is at least l(F). A needle or cap triangle (an angle near
// 0 or 180 degrees) thus caps Q min whatever a boundary-conforming mesher does: the report names
// it, so that a user can tell a poor surface from a poor mesher. (For a good triangle the bound
// exceeds 1: an equilateral one gives 2.12.)
#pragma once

#include <cstdint>

namespace tetmesher
{

// 2 sqrt(6) area / (longest edge)^2 of the triangle (a, b, c), in doubles: no tet having it as
// a face has a higher Q. 0 for a degenerate triangle (and when its edges overflow).
double triangleQualityBound(const double* a, const double* b, const double* c);

struct SurfaceQualityBound
{
  double bound = 1;           // min(1, the smallest triangleQualityBound over the triangles)
  std::int32_t triangle = -1; // the triangle giving it (the first such), -1 when bound is 1
};

// triangles: 3 point ids per triangle, into points (3 doubles per point).
SurfaceQualityBound surfaceQualityBound(const double* points,
  const std::int32_t* triangles,
  std::int32_t triangleCount);

} // namespace tetmesher
