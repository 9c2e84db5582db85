#include "SteinerRemoval.h"

#include "DeepEdgeRemoval.h"
#include "Flips.h"
#include "MeshTopology.h"
#include "Predicates.h"

#include <algorithm>

namespace tetmesher
{
namespace
{

// The star of the vertex being removed, kept up to date through the edge removals: its tets,
// its neighbours in first-seen order, and for each neighbour a star tet having the edge.
// Recomputing the star after every removed edge costs O(degree) each time, and a Steiner
// point in a nearly co-spherical mesh (vtkSphereSource's spheres: every point on one sphere)
// can have thousands of neighbours.
struct VertexStar
{
  std::vector<TetId> tets;
  std::vector<std::int32_t> position; // per tet id: its index in tets, -1 when not in it
  std::vector<VertexId> neighbours;   // live and removed ones (see neighbourTet)
  std::vector<TetId> neighbourTet;    // per vertex id: a star tet with the edge, -1: none

  void add(TetId t)
  {
    if (position.size() <= static_cast<std::size_t>(t))
      position.resize(static_cast<std::size_t>(t) + 1, -1);
    position[t] = static_cast<std::int32_t>(tets.size());
    tets.push_back(t);
  }
  void remove(TetId t)
  {
    const std::int32_t i = position[t];
    position[t] = -1;
    const TetId last = tets.back();
    tets.pop_back();
    if (last != t)
    {
      tets[static_cast<std::size_t>(i)] = last;
      position[last] = i;
    }
  }
  // Points the neighbours of v in tet t (a new star tet) at t. Edge removal never creates an
  // edge at v, so every such neighbour is already listed and live.
  void noteNeighbours(const TetMesh& mesh, TetId t, VertexId v)
  {
    for (int i = 0; i < 4; ++i)
    {
      const VertexId w = mesh.vertex(t, i);
      if (w != v && neighbourTet[w] >= 0)
        neighbourTet[w] = t;
    }
  }
};

// When each vertex last got a new tet from a kept move (a clock per vertex): a Steiner point
// that could not be removed is tried again only once a vertex its attempt examined has
// changed, as the same neighbourhood would fail the same way.
struct Changes
{
  std::vector<std::uint64_t> at;
  std::uint64_t clock = 0;

  void note(const std::vector<TetVertices>& tets)
  {
    ++clock;
    for (const TetVertices& t : tets)
      for (VertexId v : t)
        at[v] = clock;
  }
};

// Removes v by edge removals on its star and a final 4-1 flip; false (v stays, with fewer
// edges perhaps) when no edge at v can be removed on its own.
bool removeByEdgeRemovals(TetMesh& mesh,
  VertexTetIndex& index,
  VertexId v,
  VertexStar& star,
  Changes& changes)
{
  std::vector<TetId> initial;
  vertexStar(mesh, index, v, initial);
  if (initial.empty())
    return false;
  star.tets.clear();
  star.neighbours.clear();
  if (star.neighbourTet.size() < static_cast<std::size_t>(mesh.vertexCount()))
    star.neighbourTet.resize(static_cast<std::size_t>(mesh.vertexCount()), -1);
  for (TetId t : initial)
  {
    star.add(t);
    // First star tet per neighbour, as the search order: keep the earliest tet.
    for (int i = 0; i < 4; ++i)
    {
      const VertexId w = mesh.vertex(t, i);
      if (w != v && star.neighbourTet[w] < 0)
      {
        star.neighbourTet[w] = t;
        star.neighbours.push_back(w);
      }
    }
  }
  auto clearNeighbourMarks = [&]()
  {
    for (VertexId w : star.neighbours)
      star.neighbourTet[w] = -1;
    for (TetId t : star.tets)
      star.position[t] = -1;
  };
  std::size_t live = star.neighbours.size(); // neighbours whose edge to v is still there
  constexpr int kMaxRestarts = 32;
  int restarts = 0;
  FlipCost noCost;
  FlipCandidate candidate;
  std::vector<TetId> created;
  // Each successful edge removal takes one neighbour away for good (edge removal never creates
  // an edge at v), so this ends; a pass over all neighbours without one ends the attempt, as
  // an unchanged neighbourhood would fail the same way again.
  for (bool progress = true; progress;)
  {
    progress = false;
    for (std::size_t k = 0; k < star.neighbours.size(); ++k)
    {
      if (live == 4 && star.tets.size() == 4)
      {
        // 4-1 flip: v lies inside the tet of its four neighbours.
        const TetId t = star.tets[0];
        const int iv = localIndex(mesh, t, v);
        const int* fv = kFaceVertices[iv];
        const VertexId x = mesh.vertex(t, fv[0]), y = mesh.vertex(t, fv[1]),
                       z = mesh.vertex(t, fv[2]);
        VertexId u = -1;
        for (VertexId w : star.neighbours)
          if (star.neighbourTet[w] >= 0 && w != x && w != y && w != z)
            u = w;
        bool possible =
          predicates::orient3d(mesh.point(x), mesh.point(y), mesh.point(z), mesh.point(u)) > 0;
        for (TetId s : star.tets)
          for (int f = 0; f < 4 && possible; ++f)
            if (mesh.vertex(s, f) != v && mesh.isConstrained(s, f))
              possible = false; // cannot happen for a Steiner vertex
        const std::vector<TetId> old = star.tets;
        clearNeighbourMarks();
        if (!possible)
          return false;
        const std::vector<TetVertices> merged{ TetVertices{ x, y, z, u } };
        replaceTets(mesh, index, old, merged);
        changes.note(merged);
        return true;
      }
      const VertexId w = star.neighbours[k];
      const TetId t = star.neighbourTet[w];
      // The first removable edge will do (shape is the optimiser's business); taking the
      // best of all costs a DP per neighbour at every step.
      if (t < 0 || !edgeRemovalCandidate(mesh, t, v, w, noCost, candidate))
        continue;
      created.clear();
      for (TetId old : candidate.oldTets)
        star.remove(old); // every shell tet has the edge, so v
      star.neighbourTet[w] = -1;
      replaceTets(mesh, index, candidate.oldTets, candidate.newTets, &created);
      changes.note(candidate.newTets);
      for (TetId c : created)
        if (localIndex(mesh, c, v) >= 0)
        {
          star.add(c);
          star.noteNeighbours(mesh, c, v);
        }
      // w is no neighbour any more (noteNeighbours never sees it again): keep it out.
      star.neighbourTet[w] = -1;
      --live;
      progress = true;
      // Start again from the first neighbour: an edge that failed may be removable now, and
      // this order (the first removable edge in star order) is the one recovery was tuned
      // with; continuing round the list left, on Data/stator_ring.vtp, a Steiner point within
      // rounding distance of an input triangle. Each restart retries the failed prefix, so
      // past kMaxRestarts removals the passes go on round the list instead (a 300x300
      // vtkSphereSource sphere: 44 s restarting always, 6.6 s never).
      if (++restarts <= kMaxRestarts)
        k = static_cast<std::size_t>(-1);
    }
  }
  clearNeighbourMarks();
  return false;
}

// The neighbours of v, in first-seen order over its star.
void neighboursOf(const TetMesh& mesh,
  VertexTetIndex& index,
  VertexId v,
  std::vector<TetId>& star,
  std::vector<VertexId>& neighbours)
{
  vertexStar(mesh, index, v, star);
  neighbours.clear();
  for (TetId t : star)
    for (int i = 0; i < 4; ++i)
    {
      const VertexId w = mesh.vertex(t, i);
      if (w != v && std::find(neighbours.begin(), neighbours.end(), w) == neighbours.end())
        neighbours.push_back(w);
    }
}

// One edge at v removed by a flip sequence (DeepEdgeRemoval: an edge whose shell no single
// edge removal retriangulates validly, e.g. with a reflex link edge), kept only when v ends
// with fewer neighbours: the sequence may remove link edges from the other end, whose new
// edges can meet v. `attempts` bounds the sequences tried for this vertex.
bool removeOneEdgeDeep(TetMesh& mesh,
  VertexTetIndex& index,
  DeepEdgeRemoval& deep,
  VertexId v,
  int& attempts,
  Changes& changes)
{
  // Link levels and moves per sequence, as in boundary recovery.
  constexpr int kLevels = 2, kBudget = 32;
  std::vector<TetId> star;
  std::vector<VertexId> neighbours, after;
  neighboursOf(mesh, index, v, star, neighbours);
  const FlipCost noCost;
  for (VertexId w : neighbours)
  {
    if (attempts <= 0)
      return false;
    --attempts;
    deep.resetJournal();
    int budget = kBudget;
    if (deep.remove(v, w, kLevels, noCost, budget))
    {
      neighboursOf(mesh, index, v, star, after);
      if (after.size() < neighbours.size())
      {
        for (const auto& entry : deep.journal.entries)
          changes.note(entry.created);
        deep.resetJournal();
        return true;
      }
    }
    deep.undoTo(0, 0);
  }
  return false;
}

// Removes v (true), else records in `examined` the vertices whose tets the attempt saw.
bool removeVertex(TetMesh& mesh,
  VertexTetIndex& index,
  DeepEdgeRemoval& deep,
  VertexId v,
  VertexStar& star,
  Changes& changes,
  std::vector<VertexId>& examined)
{
  // Each flip sequence kept lowers v's degree, so this ends; the attempts, failed ones
  // included, are bounded too.
  constexpr int kMaxDeepAttempts = 64;
  int attempts = kMaxDeepAttempts;
  examined.clear();
  deep.seen = &examined;
  bool removed = true;
  while (removed && !removeByEdgeRemovals(mesh, index, v, star, changes))
    removed = removeOneEdgeDeep(mesh, index, deep, v, attempts, changes);
  deep.seen = nullptr;
  if (!removed)
  {
    // The edge removals looked at v's star: its neighbours.
    std::vector<TetId> tets;
    std::vector<VertexId> neighbours;
    neighboursOf(mesh, index, v, tets, neighbours);
    examined.insert(examined.end(), neighbours.begin(), neighbours.end());
    examined.push_back(v);
    std::sort(examined.begin(), examined.end());
    examined.erase(std::unique(examined.begin(), examined.end()), examined.end());
  }
  return removed;
}

} // namespace

int removeSteinerPoints(TetMesh& mesh, std::vector<VertexId>& steiner)
{
  VertexTetIndex index;
  index.rebuild(mesh);
  // Constrained faces keep the input edges: every one has its input triangles around it.
  DeepEdgeRemoval deep(mesh, index);
  // One measure (none) for the whole run, and no point moves: every candidate stays valid.
  deep.memoizeCandidates = true;
  VertexStar star;
  Changes changes;
  changes.at.assign(static_cast<std::size_t>(mesh.vertexCount()), 0);
  // A point that stays may become removable once later ones are gone: passes over the points
  // left go on while one removes something (at most kMaxPasses), each retrying only the
  // points whose examined neighbourhood changed since they failed.
  constexpr int kMaxPasses = 8;
  struct Left
  {
    VertexId v;
    std::uint64_t failedAt;
    std::vector<VertexId> examined;
  };
  std::vector<Left> left, next;
  for (VertexId v : steiner)
    left.push_back({ v, 0, {} });
  int removed = 0;
  for (int pass = 0; pass < kMaxPasses; ++pass)
  {
    const int before = removed;
    next.clear();
    for (Left& item : left)
    {
      const bool changed = pass == 0 ||
        std::any_of(item.examined.begin(),
          item.examined.end(),
          [&](VertexId w) { return changes.at[w] > item.failedAt; });
      if (!changed)
        next.push_back(std::move(item));
      else if (removeVertex(mesh, index, deep, item.v, star, changes, item.examined))
        ++removed;
      else
      {
        item.failedAt = changes.clock;
        next.push_back(std::move(item));
      }
    }
    left.swap(next);
    if (removed == before)
      break;
  }
  steiner.clear();
  for (const Left& item : left)
    steiner.push_back(item.v);
  return removed;
}

} // namespace tetmesher
