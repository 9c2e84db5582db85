// Tets that are positive in exact arithmetic but whose volume rounds to zero or below in
// double precision ("flat in doubles"). The boundary mesh of nearly co-circular or nearly
// coplanar surface points (the latitude rings of a sphere, a torus's circles) has such tets:
// exact predicates keep them valid, but the output's Quality reports them as 0 and any tool
// that measures volume in doubles (VTK's cell quality, a solver's Jacobian) sees degenerate or
// inverted cells. Flips that lower their number take most of them out without adding a point.
#pragma once

#include "MeshTopology.h"
#include "TetMesh.h"

#include <cstdint>
#include <vector>

namespace tetmesher
{

// True when tet (a,b,c,d) (TetMesh order, orient3d > 0) has a volume that is not positive
// beyond doubt in doubles (volumeCertainlyPositive in VTK order): the Quality array's 0 (its
// volume rounds to zero or below as TetQuality evaluates it), and also a tet whose computed
// volume is positive but within its rounding error (Q ~ 1e-18 on a torus's nearly planar
// quads), which another evaluation order rounds to zero or below.
bool flatInDoubles(const TetMesh& mesh, const TetVertices& t);

struct FlatTetRemovalResult
{
  int flatBefore = 0; // flat-in-doubles tets with a region, before and after
  int flatAfter = 0;
  int moves = 0; // 2-3 flips and edge removals kept
};

// Removes flat-in-doubles tets among those with tetRegion[t] >= 0 (classifyRegions: -1 for the
// exterior and holes) where flips can: first the Quality-0 ones by 2-3 flips and edge removals
// that lower their number, then the ones within rounding by such moves that lower their number
// and add no Quality-0 tet, then each Quality-0 one left by a short flip sequence that does
// the same (DeepEdgeRemoval). No vertex is added or moved, constrained faces (input triangles,
// interfaces) are never flipped, and no move crosses one, so every region and the boundary stay
// as they were; new tets take the region of the tets they replace (tetRegion grows with the
// mesh). Every kept move lowers a finite measure, and the sequences are bounded, so it ends.
FlatTetRemovalResult removeFlatTets(TetMesh& mesh, std::vector<std::int32_t>& tetRegion);

} // namespace tetmesher
