// Local transformations of George-Hecht-Saltel section 3.3: the 2-3 flip (two tets sharing a
// face -> three around the edge joining their apexes) and edge removal (the n tets around an
// edge -> 2n-4 tets over a triangulation of the edge's ring; n = 3 is the 3-2 flip, n = 4 the
// 4-4 flip). Candidates are built and priced without touching the mesh, so the caller can keep
// only the moves that make progress; every new tet is checked with exact orient3d.
#pragma once

#include "MeshTopology.h"

#include <functional>
#include <vector>

namespace tetmesher
{

// What a move is worth: each callback returns how many "obstacles" an entity of the region
// being remeshed represents (e.g. 1 if it cuts a missing input edge). Only entities interior
// to the region are priced; its boundary does not change. Null callbacks count 0.
struct FlipCost
{
  std::function<int(const TetVertices&)> tet;
  std::function<int(VertexId, VertexId, VertexId)> face;
  std::function<int(VertexId, VertexId)> edge;
};

struct FlipCandidate
{
  std::vector<TetId> oldTets;
  std::vector<TetVertices> newTets;
  int oldCost = 0;
  int newCost = 0;
  double minQuality = 0; // of the new tets, a shape measure in (0, 1]; for tie-breaking
};

// Shape measure of a tet (volume over edge lengths, 1 for the regular tet). Floating point:
// used only to choose among valid moves.
double tetShape(const TetMesh& mesh, const TetVertices& t);

// Of two moves, the one that lowers the measure more, then the better shaped.
bool betterMove(const FlipCandidate& a, const FlipCandidate& b);

// 2-3 flip of face f of tet t. False when the face is constrained or on the hull, or when the
// segment joining the two apexes does not cross the face's interior.
bool flip23Candidate(const TetMesh& mesh, TetId t, int f, const FlipCost& cost, FlipCandidate& out);

// Removal of edge (p,q) of tet t by retriangulating its shell: among the ring triangulations
// whose tets are all positive, the one of least cost (then best shape). False when the shell
// is open, a face around the edge is constrained, the ring is longer than maxRing, or no
// triangulation is valid.
bool edgeRemovalCandidate(const TetMesh& mesh,
  TetId t,
  VertexId p,
  VertexId q,
  const FlipCost& cost,
  FlipCandidate& out,
  int maxRing = 24);
// The same for the shell and ring of (p,q) that edgeShell walked (closed), for callers that
// have them already.
bool edgeRemovalCandidate(const TetMesh& mesh,
  VertexId p,
  VertexId q,
  const std::vector<TetId>& shell,
  const std::vector<VertexId>& ring,
  const FlipCost& cost,
  FlipCandidate& out,
  int maxRing = 24);

} // namespace tetmesher
