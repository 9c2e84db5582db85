// Multi-face removal for the quality optimiser (Klingner-Shewchuk 2007), the inverse of
// edge removal: m faces sandwiched between two vertices a and b (each face has a tet on
// a's side and one on b's) are removed with their 2m tets, replaced by the m+2 tets around
// the new edge ab. One face is the 2-3 flip. The face set grows greedily from one face
// across the boundary edge of the worst new tet; the best acceptable set is kept.
#pragma once

#include "OptimizationContext.h"

namespace tetmesher
{
namespace optimization
{

// The best acceptable multi-face removal grown from face f of tet t (a = t's vertex f, b the
// apex beyond the face), at most maxMultiFace faces. False when face f is constrained or on
// the hull, or when no acceptable set is found.
bool findMultiFaceRemoval(const Context& ctx, TetId t, int f, LocalMove& out);

} // namespace optimization
} // namespace tetmesher
