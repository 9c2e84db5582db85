// Boundary recovery (George-Hecht-Saltel 1990, section 3.4-3.5): turns a Delaunay mesh of the
// input points into one that has every input edge and every input triangle as a face.
//
// Strategy, in rounds:
//  0. each missing input edge first gets TetGen's directional flips (DirectionalEdgeRecovery.h:
//     the first face or edge the segment crosses is flipped away, validity alone deciding),
//     then, if still missing, the refill of the tets it cuts by a cone from one of its ends
//     as in step 3, for cavities of up to 48 tets (no new point; a flip search that fails
//     costs as much as 5-10 cone attempts);
//  1. each missing input edge, then each missing input face (whose edges exist), is recovered
//     by 2-3 flips and edge removals (n -> 2n-4, including 3-2 and 4-4) chosen greedily; a
//     move is kept only if it strictly lowers an exact integer measure of how much of the mesh
//     the missing item cuts through (tets, faces and edges it meets), so flipping ends. When
//     no move lowers it, an edge cutting the item is removed by a bounded sequence of flips
//     that never raise the measure, first flipping away the link edges that block them
//     (TetGen's flipnm, two levels deep), kept if the sequence lowers the measure or recovers
//     the item; else the shell of such an edge is shrunk by 2-3 flips, or one cost-neutral
//     move is kept if it enables an improving one (one-move lookahead). A stuck edge is
//     searched again once the mesh around it has changed (another item's flips or Steiner
//     point), and just before its own Steiner point also with its input triangles added to
//     the measure;
//  2. recovered faces are flagged constrained on both sides, so no later flip or insertion
//     removes them;
//  3. a missing edge whose flips are stuck is first recovered, where possible, by refilling
//     the tets it cuts (grown until one of its ends sees all their boundary faces) with the
//     cone from that end (CavityCone.h): no new point, and it clears flat tets that no flip
//     or Steiner cavity can take (a flat part of the surface folded by rounding);
//  4. items still missing get one Steiner point each, by constrained Delaunay insertion
//     (insertVertex), at a position strictly inside a tet the item cuts (for an edge, cut by
//     the edge alone or by the edge and its input triangles, in turn): next to the middle
//     of a mesh edge crossing it (the cavity then swallows that edge's shell), else a tet
//     centroid. A position on the input surface is never used (exact test). Next round.
// Work is bounded: per item (maxSteinerPerItem), in total (maxSteinerPoints) and per flip
// search (maxMovesPerItem); an item still missing then is reported by its id.
#pragma once

#include "SurfaceInput.h"
#include "TetMesh.h"

#include <functional>
#include <string>
#include <vector>

namespace tetmesher
{

struct RecoveryOptions
{
  int maxSteinerPoints = 1000;
  int maxMovesPerItem = 500;
  // An item still missing after this many Steiner points near it is reported as a failure:
  // on valid input a few suffice, so more means intersecting or nearly touching triangles.
  int maxSteinerPerItem = 64;
  // Wall-clock budget in seconds (0: none); exceeding it ends recovery with an error naming
  // the item being worked on.
  double maxSeconds = 0;
  // For input that was not checked: once an item has needed this many Steiner points, test
  // its triangles against all others (exactly, boxes first: O(triangles) per item) and fail
  // at once naming an intersecting pair, rather than after maxSteinerPerItem points (seconds
  // on a self-intersecting surface). 0: never.
  int intersectionProbeAfter = 0;
  // For any input: once an item has needed this many Steiner points, look for an input
  // triangle that comes closer to one of the item's triangles than nearTouchRatio times their
  // longest edge (floating point distances, boxes first: O(triangles) per item) and fail at
  // once naming the pair. Such a gap is beyond what Steiner points in doubles can resolve
  // (a fuzzed cube with a vertex 3e-39 from a face: 64 Steiner points, then failure, 1 s).
  // 0: never.
  int nearTouchProbeAfter = 8;
  double nearTouchRatio = 0x1p-40; // about 9e-13
  // Before placing a Steiner point for a missing edge, try refilling the tets it cuts by the
  // cone from one of its ends (CavityCone.h). Off: Steiner points only (for tests).
  bool refillCavities = true;
};

struct RecoveryResult
{
  bool ok = false;
  std::string error;
  std::vector<VertexId> steinerVertices; // ids of the inserted points, in insertion order
  int flips23 = 0;
  int edgeRemovals = 0;
  int neutralMoves = 0; // flips that changed nothing measured but enabled an improving one
  int cavityCones = 0;  // missing edges recovered by refilling their cavity (CavityCone.h)
  int rounds = 0;
};

// mesh: a valid triangulation of the input points (ids 0..n-1, as from buildDelaunay).
// `progress` gets the fraction of input faces recovered; returning false aborts.
RecoveryResult recoverBoundary(TetMesh& mesh,
  const SurfaceInput& surface,
  const RecoveryOptions& options,
  const std::function<bool(double)>& progress = {});

} // namespace tetmesher
