// Exhaustive, exact checks of a TetMesh, for tests and for DelaunayOptions::validate.
// Each check returns an empty string when the mesh passes, otherwise a message naming the
// first offending tet/face/vertex and what is wrong with it.
#pragma once

#include "TetMesh.h"

#include <string>
#include <vector>

namespace tetmesher
{

// Every live tet has four distinct valid vertex ids and orient3d > 0 (exact).
std::string checkOrientation(const TetMesh& mesh);

// Neighbour references point to live tets, are symmetric (n(n(t,f)) == (t,f)), and the two
// glued faces have the same three vertices. Constrained-face bits agree on both sides when
// `requireSymmetricConstraints` is set.
std::string checkAdjacency(const TetMesh& mesh, bool requireSymmetricConstraints = false);

// Every interior face is locally Delaunay under the symbolic perturbation: the vertex of
// the neighbour opposite the face is strictly outside the tet's circumsphere
// (insphereSoS < 0). Faces marked constrained are skipped when `skipConstrained` is set.
std::string checkDelaunay(const TetMesh& mesh, bool skipConstrained = true);

// Every vertex id in [0, count) that is not listed in `absent` is a vertex of a live tet.
std::string checkVerticesPresent(const TetMesh& mesh,
  VertexId count,
  const std::vector<VertexId>& absent = {});

// All of the above (Delaunay included); `count` as for checkVerticesPresent.
std::string validateDelaunayMesh(const TetMesh& mesh,
  VertexId count,
  const std::vector<VertexId>& absent = {});

// Sum of the volumes of the live tets that have no vertex with id >= firstExcluded, i.e.
// the volume of the triangulation with the box tets removed when firstExcluded is the first
// box vertex. Computed in long double (for tests; not exact).
long double volumeWithoutVertices(const TetMesh& mesh, VertexId firstExcluded);

} // namespace tetmesher
