// Triangles of an input polygon (a face of more than 3 points in a .off file or a vtkPolyData),
// made of its own points: the surface keeps its points. The same function serves the command
// line's lean path and vtkTetMesher, so both mesh a polygon alike, and neither needs VTK's
// vtkPolygon (whose libraries took ~25 ms to load for a 40-triangle .off with quads).
#pragma once

#include <cstdint>
#include <vector>

namespace tetmesher
{

// Appends to `local` the n-2 triangles of the polygon whose i-th corner is
// points[3 * ids[i] .. 3 * ids[i] + 2], as triples of corner indices 0..n-1 in the polygon's
// orientation. Ear clipping in the plane that drops the largest component of the polygon's
// (Newell) normal, with exact 2D orientations (Predicates.h): of the current ears the best
// shaped is cut first (ties: the lowest index), so a quad gets the diagonal of the better
// pair of triangles. A corner at the same coordinates as an ear's corner does not block it (a
// polygon around a hole goes along its slit twice). A polygon with no ear left (one that
// crosses itself, or folds out of its plane) or with a vanishing normal is fanned from its
// first corner instead: the input check then names what is wrong with the triangles; so is
// one with an id outside 0..pointCount-1 (the check names the id), one of more than
// kMaxEarClippedCorners corners (ear clipping takes time quadratic in n; a fuzzed face of a
// million corners must not hang), and one whose clipping exceeds a work bound of
// kEarClippingWork * n^2 orientation tests. n < 3, or n beyond 32-bit indices, appends
// nothing.
constexpr std::int64_t kMaxEarClippedCorners = 1024;
constexpr std::int64_t kEarClippingWork = 32;

// The Newell normal of the polygon of n corners points[3 * ids[i] ..] (twice its vector area),
// and the axis of its largest component (the first of equals): the plane that drops that axis
// is the one both the ear clipper and a facet's holes (Apps/FacetHoles) work in.
struct PolygonNormal
{
  double normal[3] = { 0, 0, 0 };
  int dominantAxis = 0;
};
PolygonNormal polygonNormal(const double* points, const std::int64_t* ids, std::int64_t n);

void triangulatePolygon(const double* points,
  std::int64_t pointCount,
  const std::int64_t* ids,
  std::int64_t n,
  std::vector<std::int32_t>& local);

} // namespace tetmesher
