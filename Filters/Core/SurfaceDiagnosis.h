// Diagnosis of an input triangle surface before meshing: says what is wrong and where, by the
// ids of the input points and triangles, so that the filter can refuse bad input with a message
// a user can act on (method.md, "the filter's contract").
//
// What is checked (all decisions exact, through the predicates of Predicates.h):
//  - empty input, triangles that reference point ids out of range;
//  - non-finite coordinates (NaN, Inf), coordinates outside the magnitudes for which the
//    predicates are exact (predicates::kMinExactCoordinate..kMaxExactCoordinate, and 0),
//    exactly coincident points;
//  - degenerate triangles (a repeated vertex id, or three exactly collinear points);
//  - duplicate triangles (same three vertex ids, in any order or orientation);
//  - open edges (used by one triangle);
//  - non-manifold edges that cannot bound closed regions: an edge used by 3+ triangles is a
//    valid multi-material interface (two cubes sharing a face) unless one of its triangles
//    has the same region on both sides (a dangling fin, or an internal wall). Regions are found
//    by sorting the triangles radially around every such edge, exactly;
//  - inconsistent orientation: two triangles sharing a manifold edge traverse it in the same
//    direction (a warning: the mesh does not depend on the triangles' orientation, TetGen
//    accepts such surfaces, and CGAL's *-shuffled test surfaces are exactly that);
//  - self-intersections: two triangles that meet other than in a vertex or edge they share,
//    coplanar pairs included (uniform grid over the triangle boxes, then exact tests);
//  - unused points: a warning only (ok() stays true, as for inconsistent orientation).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tetmesher
{

enum class SurfaceDefect
{
  NonFiniteCoordinate,     // pointIds: {p}
  DuplicatePoint,          // pointIds: all ids of one group of exactly equal points
  DegenerateTriangle,      // pointIds: its 3 ids; triangleIds: {t}
  DuplicateTriangle,       // pointIds: the 3 sorted ids; triangleIds: all triangles on them
  OpenEdge,                // pointIds: {a,b} (a<b); triangleIds: {t}
  NonManifoldEdge,         // pointIds: {a,b}; triangleIds: every triangle on the edge
  InconsistentOrientation, // pointIds: {a,b}; triangleIds: the two triangles (a warning)
  SelfIntersection,        // pointIds: the 6 vertex ids; triangleIds: {t1,t2} (t1<t2)
  UnusedPoint,             // pointIds: {p} (a warning: does not make ok() false)
  Empty,                   // no points or no triangles
  InvalidPointId,          // pointIds: the triangle's 3 ids; triangleIds: {t}
  CoordinateOutOfRange,    // pointIds: {p} (finite, but too large or too small to be exact)
  OutlyingPoint,           // pointIds: {p}, farther from the median point than
                           // kMaxProportion x the shortest edge (a corrupted coordinate)
  UnusedPointLeftOut,      // pointIds: {p}, used by no triangle, on the surface or equal to
                           // another point (a warning: left out of the mesh, UnusedPoints.h)
};

// Beyond this ratio of a point's distance from the surface's median point to the shortest
// edge, doubles cannot place points between the two scales: the mesher could not recover
// the edges to such a point (a fuzzed sphere with one vertex at 1e36 failed after seconds).
constexpr double kMaxProportion = 1e15;

// Short plural label of a defect kind, e.g. "open edges".
const char* defectLabel(SurfaceDefect kind, bool plural = true);
// Warnings are reported but do not make a surface unusable.
bool isWarning(SurfaceDefect kind);

struct DefectRecord
{
  SurfaceDefect kind;
  std::vector<std::int32_t> pointIds;
  std::vector<std::int32_t> triangleIds;
};

struct SurfaceDiagnosis
{
  // Grouped by kind in the order of the enum (Empty and InvalidPointId first), each kind's
  // records sorted by ids.
  std::vector<DefectRecord> defects;
  // True when some kind hit DiagnosisOptions::maxRecordsPerKind (counts are then lower bounds).
  bool truncated = false;

  bool ok() const;
  int count(SurfaceDefect kind) const;
  // The records that make the surface unusable (the warnings left out), as a diagnosis of
  // its own: what a refusal names.
  SurfaceDiagnosis errors() const;
  // One line per defect kind found, e.g.
  //   "3 open edges (points 4-7, 7-9, 9-4; triangles 12, 40, 41)"
  // with at most maxIdsPerKind entries per list. "no defects" when there are none.
  std::string summary(std::size_t maxIdsPerKind = 10) const;
};

struct DiagnosisOptions
{
  // Stop recording a kind after this many records (0: no limit). Bounds the time and memory
  // spent on hopeless input (e.g. a soup where every triangle crosses many others).
  std::size_t maxRecordsPerKind = 0;
  bool checkSelfIntersections = true;
  // TetGen's piecewise linear complexes: triangles with the same region on both sides (inner
  // facets: a free-standing sheet, a fin on a wall) are not defects, nor their open edges.
  // Whether each lies inside the volume is decided by the mesher (Mesher.h).
  bool innerFacets = false;
};

// points: 3 doubles per point; triangles: 3 point ids per triangle.
SurfaceDiagnosis diagnoseSurface(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount);
SurfaceDiagnosis diagnoseSurface(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount,
  const DiagnosisOptions& options);

} // namespace tetmesher
