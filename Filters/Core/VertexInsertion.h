// Vertex insertion for the quality optimiser (Klingner-Shewchuk 2007, simplified): a new
// vertex at the centroid of a bad tet or at the apex of the regular tet over one of its faces
// (also at half that height in the dihedral stage), connected to the boundary of a cavity
// that starts as that tet and grows greedily across the face of the worst new tet that it
// may cross (never a constrained face), keeping the best acceptable cavity: all cone tets
// positive (exact), so the cavity is star-shaped from the new vertex, and Context::accept
// against the cavity. When no position gives an acceptable cavity, the vertex is moved
// (compass search) to the best position for the best valid cavity found, which is then
// judged, and grown again from there.
#pragma once

#include "OptimizationContext.h"

namespace tetmesher
{
namespace optimization
{

// On success the new vertex is appended to ctx.mesh (and to ctx.sizeCopy, h = mean of the
// tet's) as vertex ctx.mesh.vertexCount() - 1 and `out` replaces the cavity by the cone;
// the caller applies it. On failure the mesh is unchanged.
bool findVertexInsertion(Context& ctx, TetId t, LocalMove& out, int maxCavity = 16);

} // namespace optimization
} // namespace tetmesher
