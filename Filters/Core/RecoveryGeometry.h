// Exact intersection tests used by boundary recovery: does a missing input edge or face cut
// through a mesh edge, face or tetrahedron? Every answer comes from orient3d/orient2d signs, so
// the recovery loop measures its progress without any tolerance.
//
// "Open" means relative interior: an open segment excludes its end points, an open triangle
// its edges. The tests assume what a valid mesh guarantees: no vertex lies in the relative
// interior of an edge or face it is not a vertex of.
#pragma once

namespace tetmesher
{
namespace geometry
{

// Open segment ab meets open triangle pqr (transversally, or overlapping when coplanar).
bool segmentMeetsTriangle(const double* a,
  const double* b,
  const double* p,
  const double* q,
  const double* r);

// Open segments ab and pq cross at one point interior to both (coplanar, not collinear).
bool segmentsCross(const double* a, const double* b, const double* p, const double* q);

// The relative interior of the convex hull of `count` points (2: a segment, 3: a triangle)
// meets the interior of the positively oriented tetrahedron t[0..3] (as the mesh's are).
// Points equal to a tet vertex must be passed as the same pointer (mesh coordinates).
bool simplexMeetsTetInterior(const double* const* points, int count, const double* const t[4]);
// The same by the general search for a separating plane (slower; simplexMeetsTetInterior
// decides a simplex sharing a vertex with the tet by orientations at that vertex). For tests.
bool simplexMeetsTetInteriorBySeparation(const double* const* points,
  int count,
  const double* const t[4]);

// orient3d of the tetrahedron t[0..3] with its vertex t[f] replaced by x. For a positive t:
// the side of the face opposite t[f] that x is on (> 0: t[f]'s side, 0: on its plane).
int orientWithVertexReplaced(const double* const t[4], int f, const double* x);

// The open segment (t[i], b) misses the closed tetrahedron t[0..3] (positively oriented):
// b lies strictly outside one of the three face planes through t[i], so no point of the
// segment but t[i] is in the tet's cone at t[i], which contains the tet. A quick way to rule
// out every entity of a tet at one end of a segment before testing them one by one.
bool segmentFromVertexMissesTet(const double* const t[4], int i, const double* b);

// Point x lies on the closed triangle pqr (coplanar and inside or on its edges).
bool pointOnTriangle(const double* x, const double* p, const double* q, const double* r);

// Point x lies strictly inside the positively oriented tetrahedron t[0..3].
bool pointInsideTet(const double* x, const double* const t[4]);

} // namespace geometry
} // namespace tetmesher
