// Points the user wants as vertices of the mesh, strictly inside it (TetGen's -i list, Gmsh's
// points embedded in a volume: a load, a sensor, a source). They go into the region mesh
// after the boundary mesh and before refinement, by the same constrained insertion as
// refinement's points, so refinement grades its points around them and the optimiser keeps
// them where they are. A point that cannot be a vertex strictly inside is an error naming it:
// outside the surface or in a hole, on an input triangle, edge or point, or equal to another
// given point (decided exactly).
#pragma once

#include "MeshAssembly.h"

#include <functional>
#include <string>
#include <vector>

namespace tetmesher
{

// Inserts the points of `xyz` (3 per point) into `mesh` in order; the new vertices get ids
// mesh.vertexCount() on, in that order, and their tets the region they fall in. On success
// returns "". On error returns the message (naming the point by its index in `xyz`) and leaves
// the mesh valid, with the points before it inserted. `nameVertex(v)` names an existing vertex
// the point coincides with ("input point 7").
std::string insertGivenPoints(RegionMesh& mesh,
  const std::vector<double>& xyz,
  const std::function<std::string(VertexId)>& nameVertex);

} // namespace tetmesher
