// Directional recovery of a missing input edge (a,b), as TetGen does it (Si 2015, "TetGen, a
// Delaunay-based quality tetrahedral mesh generator", section 4.2): the first mesh entity that
// the segment crosses on its way out of a's star is flipped away, chosen by direction alone:
//  - a face crossed in its interior: the 2-3 flip of that face; when that flip is invalid,
//    the removal of a face edge that blocks it (the segment from a to the apex across the
//    face passes outside that edge);
//  - an edge crossed in its interior: the removal of that edge (n tets -> 2n-4).
// Each move is checked by exact orientations; nothing is priced, so a step costs a star walk
// and a few orient3d, against the greedy flip search's pricing of every move in the item's
// pipe (ConstraintRecovery.cxx), which still takes what this leaves.
#pragma once

#include "Flips.h"
#include "MeshTopology.h"

#include <functional>
#include <vector>

namespace tetmesher
{

struct DirectionalRecoveryOptions
{
  int maxFlips = 64; // per end
};

// Flips from a towards b, then, when that stops, from b towards a, until (a,b) is an edge of
// the mesh (true) or no move applies. Moves are applied by `apply` (which must replace the
// candidate's old tets by its new ones and keep `index` valid); an edge for which
// `keepEdge(p, q)` is true is never removed, nor a constrained face (the candidates refuse
// those). Stops early (false) when the segment passes through a vertex: no flip can make it
// an edge.
bool flipEdgeIntoMesh(TetMesh& mesh,
  VertexTetIndex& index,
  VertexId a,
  VertexId b,
  const std::function<bool(VertexId, VertexId)>& keepEdge,
  const std::function<void(const FlipCandidate&, bool isFlip23)>& apply,
  const DirectionalRecoveryOptions& options = {});

} // namespace tetmesher
