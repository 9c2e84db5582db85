#include "FlatTetRemoval.h"

#include "Flips.h"
#include "TetQuality.h"

namespace tetmesher
{

bool flatInDoubles(const TetMesh& mesh, const TetVertices& t)
{
  // VTK order swaps the first two vertices.
  return !(
    tetSignedVolume(mesh.point(t[1]), mesh.point(t[0]), mesh.point(t[2]), mesh.point(t[3])) > 0);
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
  auto flatInRegion = [&](TetId t)
  {
    return !mesh.isDeleted(t) && static_cast<std::size_t>(t) < tetRegion.size() &&
      tetRegion[t] >= 0 && flatInDoubles(mesh, tetAt(t));
  };
  std::vector<TetId> queue;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (flatInRegion(t))
      queue.push_back(t);
  }
  result.flatBefore = static_cast<int>(queue.size());
  result.flatAfter = result.flatBefore;
  if (queue.empty())
    return result;

  // The measure of a move: the flat tets among those it removes or creates.
  FlipCost cost;
  cost.tet = [&mesh](const TetVertices& v) { return flatInDoubles(mesh, v) ? 1 : 0; };
  VertexTetIndex index;
  index.rebuild(mesh);
  std::vector<TetId> created;
  FlipCandidate candidate, best;
  // A queued slot may hold another tet by the time it comes up (slots are reused): it is
  // worked on if that one is flat too.
  for (std::size_t head = 0; head < queue.size(); ++head)
  {
    const TetId t = queue[head];
    if (!flatInRegion(t))
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
      if (flatInDoubles(mesh, tetAt(c)))
        queue.push_back(c);
    }
    result.flatAfter -= best.oldCost - best.newCost;
    ++result.moves;
  }
  return result;
}

} // namespace tetmesher
