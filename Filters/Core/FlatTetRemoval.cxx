#include "FlatTetRemoval.h"

#include "Flips.h"

namespace tetmesher
{

bool flatInDoubles(const TetMesh& mesh, const TetVertices& t)
{
  // VTK order swaps the first two vertices; then the volume as TetQuality computes it:
  // (b - a) . ((c - a) x (d - a)) / 6, the same operations in the same order.
  const double* p[4] = { mesh.point(t[1]), mesh.point(t[0]), mesh.point(t[2]), mesh.point(t[3]) };
  double e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      e[i][k] = p[i + 1][k] - p[0][k];
  const double x[3] = { e[1][1] * e[2][2] - e[1][2] * e[2][1],
    e[1][2] * e[2][0] - e[1][0] * e[2][2],
    e[1][0] * e[2][1] - e[1][1] * e[2][0] };
  const double volume = (e[0][0] * x[0] + e[0][1] * x[1] + e[0][2] * x[2]) / 6.0;
  return !(volume > 0);
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
