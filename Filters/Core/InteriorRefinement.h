// Interior point creation (George-Hecht-Saltel 1990, section 4.4): points are inserted inside
// the regions, with the constrained Delaunay kernel, where edges are too long for the size
// field h, until every interior edge is close to its wanted length. The boundary and the
// region interfaces (constrained faces) are never touched: no point is inserted on them and
// no cavity crosses them.
#pragma once

#include "MeshAssembly.h"
#include "SizeField.h"

#include <functional>
#include <string>
#include <vector>

namespace tetmesher
{

struct RefinementOptions
{
  SizeFieldOptions size;
  // Per region id (RegionMesh::region), an upper bound on h there (0: none); may be empty.
  // Sizes at vertices are bounded by the smallest bound of their tets' regions. meshVolume
  // sets it from the region list (MesherResult::regionMaxSize).
  std::vector<double> regionMaxSize;
  // Budget of inserted points; -1: 8 times the estimate of the field (see the .cxx), plus 16
  // per initial vertex (the layers the ceiling asks for next to small faces), plus 10000.
  int maxPoints = -1;
  // Split interior edges longer than this in units of h (l * mean(1/h_a, 1/h_b)).
  double maxEdgeRatio = 1.41421356;
  // A new point is refused when an existing vertex is closer than this, in units of h.
  double minPointDistance = 0.7;
  // ... or when a constrained face (boundary, interface) near it is closer than this.
  double minBoundaryDistance = 0.5;
  // The vertices for the test above are kept in grids of cells per size class: in arrays
  // where a class's cells are few (at most 2 per expected vertex, or 2^18), else in hash
  // tables. false: hash tables only (for tests: the answers, hence the mesh, are the same).
  bool proximityCellArrays = true;
  // The split point moves along the edge by up to +-splitJitter/2 of its length (deterministic,
  // hashed from the edge's vertex ids), so that grid-like input does not produce lattice points
  // (exactly coplanar groups that rounding turns into flat tets). 0: the metric midpoint.
  double splitJitter = 0.05;
  // Lattice prefill before the edge splitting: body-centred cubic points of spacing
  // latticeSpacing * h (2 points per cube: one per 6 regular tets' volume at 1.04 h, the
  // density of the edge-split meshes), in levels of sizes latticeLevelRatio apart where h
  // varies. 0: off.
  double latticeSpacing = 1.04;
  double latticeLevelRatio = 1.19;
  // Lattice points move by up to +-latticeJitter/2 of the spacing per coordinate
  // (deterministic, hashed from the lattice index). Exact lattice points are co-spherical
  // where the lattice is cut, so exact predicates decide there: a jitter of 0.02 saves ~20% of
  // the refinement CPU time on the unit cube at h = 1/33, but the symbolic perturbation's
  // choices suit the cut lattice better (6-cell cube at h = 1/6: 95.8% of interior edges in
  // [0.7, 1.42] h without, 94.7% with any jitter from 1e-6 to 0.02). 0: none.
  double latticeJitter = 0;
  // A lattice point is refused when a constrained face is closer than this, in units of h.
  // Larger than minBoundaryDistance: a lattice cut off at 0.5 h leaves its face diagonals
  // (1.47 h) next to the boundary, too long and unsplittable (their midpoints are 0.52 h from
  // the lattice's next layer); at 0.8 h the edge splitting fills the layer.
  double latticeBoundaryDistance = 0.8;
  // Floor under the sizes next to boundary faces larger than h (BoundarySizeFloor.h): at a
  // face, the mean length of the boundary edges at its vertices less (maxEdgeRatio - 1) h, so
  // that a face the field already matches adds nothing, and at most maxFloorRatio h, so that a
  // face far larger than h (a cube of 12 triangles at h = 1/25) still gets points of size h
  // inside; falling by floorSlope (g - 1) per unit length (off with the gradation). Chosen by
  // a sweep over 13 runs (cube.vtp at h = 0.025..0.071, a cube of 7x7 alternating quads per
  // side at 1/14..1/35, torus and icosphere at h/2): without the floor the worst min dihedral
  // was 16.4 degrees; floorSlope 1 gave Q min down to 0.285, 0.8 gives >= 0.319 and >= 28.3
  // degrees, 0.6 about the same with fewer points; a cap of 3 gave 21.6 degrees, 6 no better
  // than 4 with fewer points. maxFloorRatio <= 1 or floorSlope <= 0: off.
  double maxFloorRatio = 4;
  double floorSlope = 0.8;
  // Ceiling over the sizes next to boundary faces smaller than h (BoundarySizeCeiling.h): at a
  // face, this many times the mean length of the boundary edges at its vertices (the smallest
  // of its 3, graded), growing by (g - 1) per unit length (off with the gradation). fandisk
  // (edges 0.02) at h = 0.1: without it 45% of the tets below Q 0.3, min dihedral 5.7 degrees;
  // with 1.2, 0.003% and 25.0 degrees; 1.0 gives 0% and 25.9 but also lowers h on surfaces
  // that match it (icosphere at its edge: 12353 -> 14659 tets); 1.41 let a torus at 3 times
  // its edges fall to 19.8 degrees. <= 0: off.
  double ceilingRatio = 1.2;
  // Bound on the number of rounds (each round splits the edges too long at its start).
  int maxRounds = 200;
  // A round after the first finds its long edges (and grades the sizes) from the stars of the
  // vertices inserted or resized since, and the last round's candidates, instead of a graph
  // of every edge, when this many times their count is below the mesh's tets: the same edges,
  // tets and sizes either way (late rounds insert a few hundred points into a mesh whose graph
  // took longer to build than the rest of the round). 0: the graph every round.
  double starRoundRatio = 8;
  // Lattice rounds and edge-splitting rounds of at least this many points are inserted in two
  // halves of space side by side, on two threads where the machine has two CPUs (the mesh is
  // the same on one); fewer points, and 0, in one sequence.
  int halvesMinPoints = 4096;
  // Refuse (ok = false, before inserting any point) when the estimated memory of the refined
  // mesh exceeds this many bytes (MemoryBudget.h); <= 0: no memory check. Meshes beyond the
  // 32-bit indices (2^29 tets) are always refused. The VTK filter and the CLI pass the memory
  // available on the machine.
  double memoryLimitBytes = 0;
};

struct RefinementResult
{
  bool ok = false;
  std::string error;
  int insertedPoints = 0;
  int rounds = 0;
  double seconds = 0;
  bool budgetReached = false;   // stopped by maxPoints (the mesh is valid, just coarser)
  int rejectedNearVertex = 0;   // candidates refused: too close to a vertex
  int rejectedNearBoundary = 0; // ... too close to a constrained face
  int rejectedByKernel = 0;     // ... refused by insertVertex (on a constraint, duplicate)
  int latticePoints = 0;        // inserted points that came from the lattice prefill
  int latticeHalvesPoints = 0;  // of those, inserted by the two halves (MeshHalves)
  int latticeSecondSplits = 0;  // rounds whose rest went into halves again
  int splitHalvesPoints = 0;    // edge-splitting points inserted by the two halves
  int starRounds = 0;           // edge-splitting rounds from stars (starRoundRatio)
  bool starsRefused = false;    // a star could not be listed (a pinched domain): the graph
  double estimatedPoints = 0;   // integral of sqrt(2)/h^3 over the initial mesh (see .cxx)
  // Wall time of the parts: sizes, estimate and search grids; lattice candidates; lattice
  // insertion; edge-splitting rounds.
  double setupSeconds = 0;
  double latticeCandidateSeconds = 0;
  double latticeInsertSeconds = 0;
  double splitSeconds = 0;
};

// Inserts interior points into `mesh` until no interior edge (an edge of no constrained face;
// both ends may be boundary vertices) is longer than maxEdgeRatio in the metric of h, or no
// candidate can be inserted, or the budget is spent.
//
// vertexSize: on entry, the raw (unscaled) h of the first vertices (e.g. the input points);
// entries that are missing, <= 0 or not finite are computed: from `background` when set,
// else as the mean of the known neighbours' sizes. All sizes are then scaled and clamped by
// options.size, and the gradation is enforced over the mesh edges (lowering sizes) at the
// start of every round. On return vertexSize has one entry per vertex: the h actually used.
// New points get h interpolated (options.size.interpolationPower) in the tet that contains
// them, or background(p) (scaled and clamped) when `background` is set: it overrides the
// interpolation (controlling space / background mesh).
//
// mesh.region is kept in step: new tets take the region of the tet that contained the point
// (a cavity never crosses a constrained face). Every topological decision is exact (the
// insertion kernel); the rejection distances are floating-point heuristics.
// progress(fraction) returning false aborts (ok = false; the mesh stays valid).
RefinementResult refineInterior(RegionMesh& mesh,
  std::vector<double>& vertexSize,
  const RefinementOptions& options,
  const std::function<double(const double*)>& background = {},
  const std::function<bool(double)>& progress = {});

} // namespace tetmesher
