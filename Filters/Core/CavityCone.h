// Re-tetrahedralisation of a cavity as the cone from one of its boundary vertices, which edge
// recovery tries before it places a Steiner point. When the tets around a missing input edge (a,b)
// are flat (a planar part of the surface folded at the scale of rounding) no flip is valid and no
// Steiner point can take them into its cavity, but a cavity that contains every tet the edge cuts
// and that is star-shaped from a can be refilled by the tets (a, f) over its boundary faces f: b is
// on that boundary, so the cone has the edge (a,b). The cavity is grown across each boundary face
// that a does not strictly see, so the cone is exactly valid (TetGen refills the cavity of a
// missing face in a similar spirit, with a Delaunay mesh of its vertices instead of a cone).
#pragma once

#include "MeshTopology.h"

#include <functional>
#include <vector>

namespace tetmesher
{

struct CavityConeLimits
{
  int maxTets = 256; // cavity size at which growth gives up
};

// Grows `cavity` (live tets, modified in place) until every boundary face not incident to
// `apex` is strictly visible from it, then builds the cone in `cone`. Returns false, leaving
// the mesh untouched, when growth would cross a constrained face or the hull, exceeds the
// limit, or when the cone would not be a triangulation of the cavity that keeps all of its
// vertices, every edge `keepEdge` names, and every constrained face (checked exactly: all
// cone tets positive and its faces matched so that its boundary is the cavity's). The mesh
// is not modified: the caller replaces `cavity` by `cone` (replaceTets).
bool coneFromVertex(const TetMesh& mesh,
  VertexId apex,
  std::vector<TetId>& cavity,
  const std::function<bool(VertexId, VertexId)>& keepEdge,
  const CavityConeLimits& limits,
  std::vector<TetVertices>& cone);

} // namespace tetmesher
