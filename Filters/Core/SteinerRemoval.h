// Removal of recovery Steiner points by flips, once the boundary is recovered: a Steiner
// vertex's incident edges are removed one by one (edge removal never creates an edge at the
// vertex, so its degree drops), and when only four neighbours remain a 4-1 flip deletes it.
// When no edge at the vertex can be removed on its own, one is removed by a flip sequence
// (DeepEdgeRemoval) that lowers the vertex's degree, and the edge removals go on.
// Constrained faces are never touched, so the recovered boundary stays. A vertex whose edges
// cannot all be removed stays in the mesh, and is tried again after the others (a few passes)
// if its neighbourhood changed meanwhile.
#pragma once

#include "TetMesh.h"

#include <vector>

namespace tetmesher
{

// Tries to remove each vertex of `steiner` from the mesh; on return `steiner` lists the
// vertices that are still there. Returns how many were removed.
int removeSteinerPoints(TetMesh& mesh, std::vector<VertexId>& steiner);

} // namespace tetmesher
