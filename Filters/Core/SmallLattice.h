// Point sets on a small lattice (integer grids, voxel models, CAD parts drawn on a unit grid):
// every coordinate is lo[k] + i * 2^L with 0 <= i < 2^9. For such points the in-sphere and
// orientation determinants, evaluated in doubles from the coordinate differences, are exact:
// the differences are integers times 2^L below 2^9 in magnitude, and every intermediate value
// of the in-sphere determinant is below 72 * 2^45 < 2^53 times 2^(5L) (orient3d: 6 * 2^27),
// so no operation rounds. The sign of the double result is then the exact sign, zero
// included, with no error bound to compute and no exact fallback; where it is zero the
// symbolic perturbation decides, by orientations that are exact in doubles too.
//
// Such input is fully degenerate (co-spherical everywhere), so the general predicates fail
// their filter on a large share of the tests and pay the exact stages and the tie break.
#pragma once

#include "FilteredPredicates.h"
#include "TetMesh.h"

namespace tetmesher
{

// The bits (1..9) that the lattice indices of the n points need, when every coordinate is
// lo[k] plus an integer multiple of a common power of two below 2^9 times it (lo: the
// points' lower corner); 0 otherwise (also for n = 0 and one point repeated).
int smallLatticeBits(const double* points, VertexId n, const double lo[3]);

namespace predicates
{

// orient3d of points on one small lattice (see above): exact in doubles.
inline int orient3dSmallLattice(const double* a, const double* b, const double* c, const double* d)
{
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
  const double det =
    adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
  return (det > 0) - (det < 0);
}

// insphereSoSFiltered (FilteredPredicates.h) for five points of one small lattice: the same
// answers, the determinant and the tie break's orientations evaluated in doubles alone.
inline int insphereSoSSmallLattice(const double* coords,
  VertexId a,
  VertexId b,
  VertexId c,
  VertexId d,
  VertexId e,
  const VertexId* perturbationIds)
{
  const double* p[5] = { coords + 3 * static_cast<std::size_t>(a),
    coords + 3 * static_cast<std::size_t>(b),
    coords + 3 * static_cast<std::size_t>(c),
    coords + 3 * static_cast<std::size_t>(d),
    coords + 3 * static_cast<std::size_t>(e) };
  // Exact in any order of operations (no operation rounds), so the filter's evaluation in
  // lanes serves; the permanent it would add is dead code here.
  const InsphereTerms terms = insphereTerms(p[0], p[1], p[2], p[3], p[4]);
  const double det = terms.det;
  if (det != 0)
    return det > 0 ? 1 : -1;
  // The tie break from the minors, exact here (FilteredPredicates.h).
  VertexId ids[5] = { a, b, c, d, e };
  if (perturbationIds)
    for (VertexId& id : ids)
      id = perturbationIds[id];
  const double* m = terms.cofactor;
  return tieBreakFromMinors(m[0], m[1], m[2], m[3], m[0] - m[1] + m[2] - m[3], ids);
}

} // namespace predicates
} // namespace tetmesher
