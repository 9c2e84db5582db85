// The order of the symbolic perturbation for the Delaunay of a surface's points, chosen so
// that ties pick the surface's own diagonals. On planar parts of CAD surfaces four points of
// two coplanar input triangles (a,b,c) and (a,b,d) are often co-circular (the rectangles of a
// gear's teeth, any regular grid): the in-sphere test is then an exact tie, and the
// perturbation decides which diagonal of the quad the Delaunay mesh has. With the lifting
// rule of insphereSoS the quad gets the diagonal that avoids its highest-ranked vertex, so the
// input edge (a,b) is there when c or d outranks both a and b. Otherwise recovery has to flip
// it in, which on such quads often fails and costs a Steiner point (gear.vtp: 82 edges).
// Only ties depend on the order: on input without them the mesh is the same.
#pragma once

#include "SurfaceInput.h"
#include "TetMesh.h"

#include <vector>

namespace tetmesher
{

struct PerturbationOrder
{
  // rank[v] for each surface point v: a permutation of 0..pointCount-1 (insphereSoS
  // perturbs the highest rank most). Empty when the surface has no such quad (use the ids).
  std::vector<VertexId> rank;
  int quads = 0;     // co-circular coplanar quads around an input edge
  int satisfied = 0; // of those, the ones whose input diagonal the order selects
};

// Ranks the points from the top down, each time taking a point that is no endpoint of the
// diagonal of a quad still without a ranked vertex (the highest id among them, so that points
// in no quad keep the order of their ids); when there is none, one that is for the fewest.
PerturbationOrder perturbationOrderForSurface(const double* points, const SurfaceInput& surface);

} // namespace tetmesher
