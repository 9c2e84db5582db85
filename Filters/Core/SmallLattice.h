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
  const double* pe = p[4];
  const double aex = p[0][0] - pe[0], bex = p[1][0] - pe[0], cex = p[2][0] - pe[0],
               dex = p[3][0] - pe[0];
  const double aey = p[0][1] - pe[1], bey = p[1][1] - pe[1], cey = p[2][1] - pe[1],
               dey = p[3][1] - pe[1];
  const double aez = p[0][2] - pe[2], bez = p[1][2] - pe[2], cez = p[2][2] - pe[2],
               dez = p[3][2] - pe[2];
  const double ab = aex * bey - bex * aey, bc = bex * cey - cex * bey;
  const double cd = cex * dey - dex * cey, da = dex * aey - aex * dey;
  const double ac = aex * cey - cex * aey, bd = bex * dey - dex * bey;
  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;
  const double alift = aex * aex + aey * aey + aez * aez;
  const double blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez;
  const double dlift = dex * dex + dey * dey + dez * dez;
  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  if (det != 0)
    return det > 0 ? 1 : -1;
  // The tie break from the minors, exact here (FilteredPredicates.h).
  VertexId ids[5] = { a, b, c, d, e };
  if (perturbationIds)
    for (VertexId& id : ids)
      id = perturbationIds[id];
  return tieBreakFromMinors(abc, bcd, cda, dab, abc - bcd + cda - dab, ids);
}

} // namespace predicates
} // namespace tetmesher
