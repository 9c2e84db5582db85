#include "SteinerRemoval.h"

#include "Flips.h"
#include "MeshTopology.h"
#include "Predicates.h"

#include <algorithm>

namespace tetmesher
{
namespace
{

bool removeVertex(TetMesh& mesh, VertexTetIndex& index, VertexId v)
{
  std::vector<TetId> star;
  FlipCost noCost;
  // Each successful edge removal lowers the degree of v by one, so this loop is bounded.
  while (true)
  {
    vertexStar(mesh, index, v, star);
    if (star.empty())
      return false;
    std::vector<VertexId> neighbours;
    for (TetId t : star)
    {
      for (int i = 0; i < 4; ++i)
      {
        VertexId w = mesh.vertex(t, i);
        if (w != v && std::find(neighbours.begin(), neighbours.end(), w) == neighbours.end())
          neighbours.push_back(w);
      }
    }
    if (neighbours.size() == 4 && star.size() == 4)
    {
      // 4-1 flip: v lies inside the tet of its four neighbours.
      TetId t = star[0];
      int iv = localIndex(mesh, t, v);
      const int* fv = kFaceVertices[iv];
      VertexId x = mesh.vertex(t, fv[0]), y = mesh.vertex(t, fv[1]), z = mesh.vertex(t, fv[2]);
      VertexId w = -1;
      for (VertexId u : neighbours)
      {
        if (u != x && u != y && u != z)
          w = u;
      }
      TetVertices merged = { x, y, z, w };
      if (predicates::orient3d(mesh.point(x), mesh.point(y), mesh.point(z), mesh.point(w)) <= 0)
        return false;
      for (TetId s : star)
      {
        for (int f = 0; f < 4; ++f)
        {
          if (mesh.vertex(s, f) != v && mesh.isConstrained(s, f))
            return false; // an inner face is constrained: cannot happen for a Steiner vertex
        }
      }
      replaceTets(mesh, index, star, { merged });
      return true;
    }
    FlipCandidate best, candidate;
    bool found = false;
    for (VertexId w : neighbours)
    {
      TetId t = -1;
      for (TetId s : star)
      {
        if (localIndex(mesh, s, w) >= 0)
        {
          t = s;
          break;
        }
      }
      // The first removable edge will do (shape is the optimiser's business); taking the
      // best of all costs a DP per neighbour at every step.
      if (edgeRemovalCandidate(mesh, t, v, w, noCost, candidate))
      {
        best = candidate;
        found = true;
        break;
      }
    }
    if (!found)
      return false;
    replaceTets(mesh, index, best.oldTets, best.newTets);
  }
}

} // namespace

int removeSteinerPoints(TetMesh& mesh, std::vector<VertexId>& steiner)
{
  VertexTetIndex index;
  index.rebuild(mesh);
  std::vector<VertexId> kept;
  int removed = 0;
  for (VertexId v : steiner)
  {
    if (removeVertex(mesh, index, v))
      ++removed;
    else
      kept.push_back(v);
  }
  steiner.swap(kept);
  return removed;
}

} // namespace tetmesher
