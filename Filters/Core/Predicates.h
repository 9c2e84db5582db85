// Exact geometric predicates. Every topological decision of the mesher goes through these:
// a floating-point filter with a proven error bound decides the easy cases, exact expansion
// arithmetic decides the rest. No epsilon anywhere.
#pragma once

#include "TetMesh.h"

#include <cstdint>
#include <string>

namespace tetmesher
{
namespace predicates
{

// The magnitudes of coordinates for which the predicates below are exact. The expansion
// arithmetic is exact only while no product overflows or underflows: insphere is of degree 5
// in the coordinates (and the Delaunay box corners lie up to 3x farther out than the points),
// so beyond 1e50 it overflows; below 1e-40 the low bits of its degree-5 products fall under
// the smallest double. Zero is always fine. Inputs are checked against this range
// (buildDelaunay, buildSurfaceInput, diagnoseSurface) and refused outside it.
constexpr double kMaxExactCoordinate = 1e50;
constexpr double kMinExactCoordinate = 1e-40;
inline bool inExactRange(double c)
{
  const double a = c < 0 ? -c : c;
  return a == 0 || (a >= kMinExactCoordinate && a <= kMaxExactCoordinate);
}
// "" when every coordinate of points[0..3n) is finite and in the exact range, otherwise a
// message naming the first offending point (as "`noun` i") and its coordinate.
std::string coordinateRangeError(const double* points, std::int64_t pointCount, const char* noun);

// Sign of det[a-d; b-d; c-d]: +1 when d lies below the plane through a,b,c (a,b,c
// counterclockwise seen from above), -1 above, 0 when the four points are coplanar.
// Exact for every double input in the exact range above.
int orient3d(const double* a, const double* b, const double* c, const double* d);

// For a positively oriented tet (a,b,c,d): +1 when e is strictly inside its circumsphere,
// -1 outside, 0 on it. Exact.
int insphere(const double* a, const double* b, const double* c, const double* d, const double* e);

// Sign of the 2D orientation of a,b,c projected on the coordinate plane that drops axis
// `dropAxis` (0,1,2). Exact. Used for coplanar configurations. The remaining axes are taken
// in cyclic order (drop z: (x,y); drop x: (y,z); drop y: (z,x)), so the sign is the sign of
// the dropped-axis component of the normal (b-a)x(c-a).
int orient2d(const double* a, const double* b, const double* c, int dropAxis);

// In-sphere with symbolic perturbation (simulation of simplicity on the lifted points, by
// vertex id): never returns 0 for five distinct points, and is consistent, so co-spherical
// input (grids, boxes) gives one well-defined Delaunay triangulation. Points are looked up
// in mesh.coords by id; (a,b,c,d) must be positively oriented.
// The rule (Edelsbrunner-Muecke): vertex i's lifted coordinate |p_i|^2 is raised by
// eps^(K - i), so the largest id is perturbed most. On an exact tie the answer is the sign of
// the first non-zero cofactor by decreasing id: -orient3d(a,b,c,d) for e, and for a vertex x
// of (a,b,c,d), orient3d of (a,b,c,d) with x replaced by e. See Predicates.cxx.
int insphereSoS(const TetMesh& mesh, VertexId a, VertexId b, VertexId c, VertexId d, VertexId e);

} // namespace predicates
} // namespace tetmesher
