#include "FlatTetRemoval.h"

#include "DeepEdgeRemoval.h"
#include "Flips.h"
#include "TetQuality.h"

#include <functional>

namespace tetmesher
{

bool flatInDoubles(const TetMesh& mesh, const TetVertices& t)
{
  // VTK order swaps the first two vertices.
  return !volumeCertainlyPositive(
    mesh.point(t[1]), mesh.point(t[0]), mesh.point(t[2]), mesh.point(t[3]));
}

FlatTetRemovalResult removeFlatTets(TetMesh& mesh, std::vector<std::int32_t>& tetRegion)
{
  FlatTetRemovalResult result;
  auto tetAt = [&](TetId t)
  {
    return TetVertices{
      mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3)
    };
  };
  // Quality 0: the volume rounds to zero or below as TetQuality evaluates it (VTK order).
  auto qualityZero = [&mesh](const TetVertices& v)
  {
    return !(
      tetSignedVolume(mesh.point(v[1]), mesh.point(v[0]), mesh.point(v[2]), mesh.point(v[3])) > 0);
  };
  auto inRegion = [&](TetId t)
  {
    return !mesh.isDeleted(t) && static_cast<std::size_t>(t) < tetRegion.size() &&
      tetRegion[t] >= 0;
  };
  auto countFlat = [&]
  {
    int n = 0;
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
      n += inRegion(t) && flatInDoubles(mesh, tetAt(t)) ? 1 : 0;
    return n;
  };
  result.flatBefore = countFlat();
  result.flatAfter = result.flatBefore;
  if (result.flatBefore == 0)
    return result;
  VertexTetIndex index;
  index.rebuild(mesh);
  std::vector<TetId> created, queue;
  FlipCandidate candidate, best;
  // One pass: the tets `isFlat` names, by moves that lower `cost` (so at most as many moves
  // as the cost of the tets queued at its start, each lowers it by at least one).
  // The tets of the regions that isFlat names, into `queue`.
  auto collect = [&](const std::function<bool(const TetVertices&)>& isFlat)
  {
    queue.clear();
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
      if (inRegion(t) && isFlat(tetAt(t)))
        queue.push_back(t);
  };
  auto pass = [&](const std::function<bool(const TetVertices&)>& isFlat, const FlipCost& cost)
  {
    collect(isFlat);
    // A queued slot may hold another tet by the time it comes up (slots are reused): it is
    // worked on if that one is flat too.
    for (std::size_t head = 0; head < queue.size(); ++head)
    {
      const TetId t = queue[head];
      if (!inRegion(t) || !isFlat(tetAt(t)))
        continue;
      const TetVertices v = tetAt(t);
      bool found = false;
      auto consider = [&]
      {
        if (candidate.oldCost > candidate.newCost && (!found || betterMove(candidate, best)))
        {
          best = candidate;
          found = true;
        }
      };
      for (int f = 0; f < 4; ++f)
      {
        if (flip23Candidate(mesh, t, f, cost, candidate))
          consider();
      }
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
        {
          if (edgeRemovalCandidate(mesh, t, v[i], v[j], cost, candidate))
            consider();
        }
      if (!found)
        continue;
      // All tets of a move share t's region: the move never crosses a constrained face.
      const std::int32_t region = tetRegion[t];
      replaceTets(mesh, index, best.oldTets, best.newTets, &created);
      if (tetRegion.size() < static_cast<std::size_t>(mesh.tetCapacity()))
        tetRegion.resize(static_cast<std::size_t>(mesh.tetCapacity()), -1);
      for (TetId c : created)
      {
        tetRegion[c] = region;
        if (isFlat(tetAt(c)))
          queue.push_back(c);
      }
      ++result.moves;
    }
  };
  // First the Quality-0 tets, by moves that lower their number.
  FlipCost zeroCost;
  zeroCost.tet = [&](const TetVertices& v) { return qualityZero(v) ? 1 : 0; };
  pass(qualityZero, zeroCost);
  // Then the ones within rounding (Q ~ 1e-18 on a torus's nearly planar quads: 546 in its
  // boundary mesh, against 12 of Quality 0), by moves that lower their number and never add a
  // Quality-0 tet: one of those outweighs all that a move can create of the others (an edge
  // removal creates at most 16 tets).
  constexpr int kQualityZeroWeight = 32;
  FlipCost roundingCost;
  roundingCost.tet = [&](const TetVertices& v) {
    return !flatInDoubles(mesh, v) ? 0 : qualityZero(v) ? kQualityZeroWeight : 1;
  };
  pass([&](const TetVertices& v) { return flatInDoubles(mesh, v); }, roundingCost);
  // Last, each Quality-0 tet left gets the removal of one of its edges by a short sequence of
  // moves (DeepEdgeRemoval, TetGen's flipnm: one link level, 8 shells) that never raises the
  // measure above, kept when it lowers it. Over Data/ (boundary only) Quality 0 83 -> 37 for
  // about 0.5% more instructions on the smooth surfaces; the same for every tet within
  // rounding also took those 2361 -> 1593, for 8% more on helix_tube (2026-12-02).
  constexpr int kDeepLevels = 1, kDeepShells = 8;
  DeepEdgeRemoval deep(mesh, index);
  std::int32_t region = -1;
  // Every move stays in the region of the tet it started from (none crosses a constrained
  // face), undone ones too.
  deep.onCreated = [&](TetId c)
  {
    if (tetRegion.size() < static_cast<std::size_t>(mesh.tetCapacity()))
      tetRegion.resize(static_cast<std::size_t>(mesh.tetCapacity()), -1);
    tetRegion[c] = region;
  };
  collect(qualityZero);
  for (TetId t : queue)
  {
    if (!inRegion(t) || !qualityZero(tetAt(t)))
      continue;
    const TetVertices v = tetAt(t);
    region = tetRegion[t];
    bool kept = false;
    for (int i = 0; i < 4 && !kept; ++i)
      for (int j = i + 1; j < 4 && !kept; ++j)
      {
        deep.resetJournal();
        int budget = kDeepShells;
        kept = deep.remove(v[i], v[j], kDeepLevels, roundingCost, budget) && deep.journal.delta < 0;
        if (kept)
          result.moves += static_cast<int>(deep.journal.entries.size());
        else
          deep.undoTo(0, 0);
      }
  }
  result.flatAfter = countFlat();
  return result;
}

} // namespace tetmesher
