#include "SteinerRemoval.h"

#include "Flips.h"
#include "MeshTopology.h"
#include "Predicates.h"

#include <algorithm>

namespace tetmesher
{
namespace
{

// Per-vertex scratch marks (stamps) for collecting the neighbours of a vertex in linear time.
struct NeighbourMarks
{
  std::vector<std::uint32_t> stamp;
  std::uint32_t epoch = 0;
};

bool removeVertex(TetMesh& mesh, VertexTetIndex& index, VertexId v, NeighbourMarks& marks)
{
  std::vector<TetId> star;
  std::vector<TetId> firstTet; // per neighbour: the first star tet having it
  FlipCost noCost;
  if (marks.stamp.size() < static_cast<std::size_t>(mesh.vertexCount()))
    marks.stamp.resize(mesh.vertexCount(), 0);
  // Each successful edge removal lowers the degree of v by one, so this loop is bounded.
  while (true)
  {
    vertexStar(mesh, index, v, star);
    if (star.empty())
      return false;
    std::vector<VertexId> neighbours;
    firstTet.clear();
    if (++marks.epoch == 0)
    {
      std::fill(marks.stamp.begin(), marks.stamp.end(), 0u);
      marks.epoch = 1;
    }
    for (TetId t : star)
    {
      for (int i = 0; i < 4; ++i)
      {
        VertexId w = mesh.vertex(t, i);
        if (w != v && marks.stamp[w] != marks.epoch)
        {
          marks.stamp[w] = marks.epoch;
          neighbours.push_back(w);
          firstTet.push_back(t);
        }
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
    for (std::size_t k = 0; k < neighbours.size(); ++k)
    {
      VertexId w = neighbours[k];
      TetId t = firstTet[k];
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
  NeighbourMarks marks;
  int removed = 0;
  for (VertexId v : steiner)
  {
    if (removeVertex(mesh, index, v, marks))
      ++removed;
    else
      kept.push_back(v);
  }
  steiner.swap(kept);
  return removed;
}

} // namespace tetmesher
