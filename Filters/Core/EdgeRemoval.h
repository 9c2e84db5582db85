// Edge removal for the quality optimiser (Shewchuk, "Two discrete optimization algorithms
// for the topological improvement of tetrahedral meshes"; Klingner-Shewchuk 2007): the n
// tets around an interior edge pq are replaced by the 2n-4 tets (r_i, r_j, r_k, q) and
// (r_j, r_i, r_k, p) over the triangulation of the ring polygon r_0..r_{n-1} that maximises
// the worst quality, found by dynamic programming over the polygon's sub-chains (O(n^3)).
// n = 3 is the 3-2 flip.
#pragma once

#include "OptimizationContext.h"

namespace tetmesher
{
namespace optimization
{

// Best retriangulation of the shell of edge (p,q) of tet t, when it is acceptable
// (Context::accept against the shell) and all its tets are positive. False when the shell is
// open, a face around the edge is constrained, or the ring is longer than maxEdgeRing.
bool findEdgeRemoval(const Context& ctx, TetId t, VertexId p, VertexId q, LocalMove& out);

} // namespace optimization
} // namespace tetmesher
