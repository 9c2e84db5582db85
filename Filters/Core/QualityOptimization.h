// Quality optimisation of a tetrahedral mesh (George-Hecht-Saltel 1990, sections 4.3 and 4.5;
// after Klingner & Shewchuk 2007, "Aggressive tetrahedral mesh improvement").
//
// Driven by the worst elements. Each pass works through a queue of the tets whose quality
// is below the target, worst first (new bad tets are queued behind; a tet is in the queue
// once at most), applying the best acceptable of
//  - edge removal of each of its edges (EdgeRemoval.h): the n tets around an interior edge
//    become the 2n-4 tets over the best triangulation of the edge's ring (dynamic programming
//    over the ring polygon, maximising the worst quality); n = 3 is the 3-2 flip;
//  - multi-face removal from each of its faces (MultiFaceRemoval.h), the inverse of edge
//    removal; one face is the 2-3 flip;
// and, when none applies, smoothing of its free vertices; then, when options.insertion is
// set, vertex insertion (VertexInsertion.h) at that tet (and at every bad tet for one more
// pass when a pass changed nothing). When more than a tenth of the tets are bad, a pass
// starts with a smoothing sweep over the bad tets' vertices. Searches that failed are not
// repeated until a tet around them changes. Vertex smoothing (VertexSmoothing.h): the paper's
// weighted barycentre of the ball (volume-weighted centroids; mean of ideal apexes), then
// ascent on the worst quality of the ball along the least-norm point of the hull of the
// nearly-worst tets' gradients. Passes stop early when nothing changes.
//
// The acceptance rule (OptimizationContext.h): every new tet positively oriented (exact
// orient3d), the worst quality of the changed set strictly improves in the chosen measure,
// and neither the set's worst Q nor its worst dihedral angle falls below both its old value
// and the mesh minimum at the start of the pass. Hence the mesh's minimum Q and minimum
// dihedral angle never decrease. Constrained faces (boundary and region interfaces) are never
// removed and their vertices never move, so the boundary and the interfaces stay
// bit-identical, every change stays inside one region, and no vertex leaves the mesh.
#pragma once

#include "MeshAssembly.h"

#include <functional>
#include <string>
#include <vector>

namespace tetmesher
{

enum class QualityMeasure
{
  PaperQ,     // 2*sqrt(6) r_in / l_max (size-scaled when a size field is given); default
  MinDihedral // the smallest dihedral angle, divided by the regular tet's (70.53 degrees)
};

struct OptimizationOptions
{
  int passes = 3; // rounds of (smoothing, topological moves) over the bad tets
  // Work on tets whose measure (in [0,1]) is below this. 0.35 rather than the 0.3 users
  // check against: the margin is what lets the dihedral stage move vertices without pushing
  // tets below Q 0.3 (on the test surfaces: share of Q < 0.3 back to 0, and 2-7 degrees more
  // on the smallest dihedral angle than with 0.3).
  double qualityTarget = 0.35;
  QualityMeasure measure = QualityMeasure::PaperQ;
  bool smoothing = true;
  bool flips = true;
  // Vertex insertion once the other moves stall (needs flips): adds interior vertices, so
  // the mesh gets vertices beyond vertexSize's (their h: mean of the split tet's). A last
  // resort for the few tets nothing else fixes, such as a flat tet spanning two nearly
  // coplanar surface triangles (fandisk at h = 0.0207: Q min 0.0018 without, 0.350 with).
  bool insertion = true;
  // Most vertices one stage may insert; -1: 10 + 1 per 1000 tets of its input. Unbounded,
  // insertion adds thousands of points on surfaces with poor triangles, where no placement
  // lifts the tets on the surface (Data/gear.vtp: 7.6k -> 18k tets, 5.7 -> 25 s), and
  // doubles the time of fine meshes for a gain in the third decimal of Q min. Bounded, gear
  // gets 270 more tets and Q min 0.056 instead of 0.0075, and the optimiser, no longer
  // stalled, works up to its work bound (VolumeMeshOptions::optimizationPolls).
  int maxInsertedVertices = -1;
  // Vertices that never move besides those on constrained faces (given interior points).
  std::vector<VertexId> fixedVertices;
  int maxEdgeRing = 10; // longest edge ring that edge removal retriangulates
  int maxMultiFace = 8; // most faces one multi-face removal takes out (1: 2-3 flips only)
  // Gradient-ascent steps per vertex after the barycentre. 2 rather than 8: a vertex is
  // smoothed again whenever its ball changes, so later steps mostly redo what the next visit
  // does anyway; on the sized benchmark's cases the minimum angles stayed within noise of
  // 8 steps (torus at h/2: 20.4 -> 22.2 degrees) for about 0.6x the smoothing time.
  int smoothingSteps = 2;
  // Bounds on smoothing moves per pass (a stage runs `passes` of them): one vertex moves at
  // most maxSmoothingMovesPerVertex times, and all vertices together at most
  // smoothingMovesPerFreeVertex x (the vertices free to move) times, never fewer than 1000;
  // past them the pass goes on with topological moves alone. On surfaces with poor
  // triangles most tets stay below the target whatever is done, and each move requeues the
  // ball's bad tets, so neighbouring vertices traded small gains back and forth: 27 moves
  // per interior vertex on Data/turbine.off (optimisation 3.9 of its 4.8 s), ~100 on
  // rotor_small. Bounded, the default-size optimisation of turbine takes 1.9 s, alternator
  // 2.4 s (6.2), couplingdown 1.2 s (5.6), pinion_small 0.7 s (3.4); the share of tets
  // below Q 0.3 fell on the first three and rose on pinion_small (50.7 -> 55.1%), and the
  // sized benchmark's good surfaces never reach the bounds (same meshes). 6 per vertex was
  // faster still (turbine 1.5 s) but changed the meshes of good surfaces (torus.vtp Q min
  // 0.352 -> 0.345); 1 per free vertex cost rotor_small's Q min (0.0102 -> 0.0077). <= 0: no
  // bound.
  int maxSmoothingMovesPerVertex = 12;
  double smoothingMovesPerFreeVertex = 2.0;
  // With PaperQ: when > 0 (degrees), a second stage follows, driven by the smallest dihedral
  // angle, with the minimum Q reached by the first stage guarded. It works on the tets below
  // 1.2 x dihedralTarget (qualityTarget = 1.2 * dihedralTarget / 70.53): working past the
  // target is what gets the tets it cannot lift as far (mostly on coarse boundary triangles)
  // to it. Counters add up over both stages. On by default; 25 (worked to 30) rather than 20
  // for the same reason.
  double dihedralTarget = 25;
  // A pass with at least this many tets below the target works in two halves of space side
  // by side, on two threads where the machine has two CPUs (the mesh is the same on one),
  // then works what needs both halves in one sequence; fewer, and 0, in one sequence.
  int halvesMinBadTets = 1024;
  // Gives, in OptimizationResult::qualityBefore, the Q of every live tet before any move
  // (measureTetQuality's: without the sizes), from the optimiser's own first measure of every
  // tet instead of a scan of its own.
  bool recordQualityBefore = false;
};

struct OptimizationResult
{
  bool ok = true;
  std::string error;
  // Q is the paper's measure (size-scaled when vertexSize is given), whatever the driving
  // measure; dihedral angles in degrees. Over the live tets.
  double minQualityBefore = 0, minQualityAfter = 0;
  double meanBefore = 0, meanAfter = 0;
  double minDihedralBefore = 0, minDihedralAfter = 0;
  double shareBelowTargetBefore = 0, shareBelowTargetAfter = 0; // by the driving measure
  int tetsBefore = 0, tetsAfter = 0;
  int flips23 = 0, flips32 = 0, edgeRemovals = 0, smoothedVertices = 0;
  int multiFaceRemovals = 0; // more than one face (one face: flips23)
  int insertedVertices = 0;  // by vertex insertion (options.insertion)
  int passesRun = 0;         // passes that worked on bad tets
  int passesInHalves = 0;    // of passesRun (OptimizationOptions::halvesMinBadTets)
  // Stages ended before their passes were done because a pass changed tets but neither raised
  // the minimum nor left fewer tets below the target (a poor surface bounds them).
  int stagesEndedWithoutGain = 0;
  double seconds = 0;
  // With OptimizationOptions::recordQualityBefore: measureTetQuality of each live tet (VTK's
  // vertex order, no sizes) before the first move, in slot order; else empty.
  std::vector<double> qualityBefore;
};

// Improves the worst elements of `mesh` in place. `vertexSize` (optional, h > 0 per vertex)
// makes the quality size-scaled (measureTetScaled). `progress` gets a fraction in [0,1] after
// each pass; returning false stops early (ok = false, error = "aborted"; the mesh is valid).
// Requires mesh.region to have one entry per tet slot (it is resized to the capacity).
OptimizationResult optimizeMesh(RegionMesh& mesh,
  const OptimizationOptions& options,
  const std::vector<double>* vertexSize = nullptr,
  const std::function<bool(double)>& progress = {});

} // namespace tetmesher
