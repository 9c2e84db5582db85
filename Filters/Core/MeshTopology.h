// Local topology queries and edits on a TetMesh that the recovery stage needs: a vertex ->
// tet index, vertex stars, edge and face look-up, the ordered shell of tets around an edge,
// and a generic "replace these tets by those" that re-glues neighbours and keeps the
// constraint flags of the faces on the replaced region's boundary.
#pragma once

#include "TetMesh.h"

#include <algorithm>
#include <array>
#include <vector>

namespace tetmesher
{

using TetVertices = std::array<VertexId, 4>;

// One incident live tet per vertex, repaired lazily: a stale entry (deleted tet, reused slot)
// triggers a full rebuild, so callers may edit the mesh freely between queries.
class VertexTetIndex
{
public:
  void rebuild(const TetMesh& mesh);
  // A live tet incident to v, or -1 when v is in no tet (e.g. a duplicate point).
  TetId tetOf(const TetMesh& mesh, VertexId v);
  // Inline: every new tet of every move (made or undone) is noted.
  void note(TetId t, const TetMesh& mesh)
  {
    if (static_cast<VertexId>(vertexTet_.size()) < mesh.vertexCount())
      vertexTet_.resize(mesh.vertexCount(), -1);
    for (int i = 0; i < 4; ++i)
      vertexTet_[mesh.vertex(t, i)] = t;
  }

  // Visit marks for one traversal at a time (stamps, so starting one is O(1)). Inline: the
  // flip searches walk stars and shells all the time.
  void startVisit()
  {
    if (++epoch_ == 0)
      resetStamps();
  }
  // True the first time t is visited in the current traversal.
  bool visit(TetId t)
  {
    if (static_cast<std::size_t>(t) >= stamp_.size())
      // An eighth more, not double: every entry is written (zeros), and the vector's own
      // growth keeps the resizes few (two indexes over fandisk at h/2's tets: 19 -> 11 MB).
      stamp_.resize(static_cast<std::size_t>(t) + static_cast<std::size_t>(t) / 8 + 16, 0u);
    if (stamp_[t] == epoch_)
      return false;
    stamp_[t] = epoch_;
    return true;
  }

  // The entries of `other` (not its visit marks): a second index over the same mesh, for a
  // thread of its own.
  void copyEntries(const VertexTetIndex& other) { vertexTet_ = other.vertexTet_; }
  // Takes other's entry for every vertex v < vertexCount with takes(v).
  template<typename Takes>
  void takeEntries(const VertexTetIndex& other, const Takes& takes)
  {
    for (std::size_t v = 0; v < vertexTet_.size() && v < other.vertexTet_.size(); ++v)
      if (takes(static_cast<VertexId>(v)))
        vertexTet_[v] = other.vertexTet_[v];
  }

private:
  void resetStamps();
  std::vector<TetId> vertexTet_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;
};

// Local index (0..3) of v in tet t, or -1.
inline int localIndex(const TetMesh& mesh, TetId t, VertexId v)
{
  const VertexId* tet = &mesh.tets[4 * static_cast<std::size_t>(t)];
  return tet[0] == v ? 0 : tet[1] == v ? 1 : tet[2] == v ? 2 : tet[3] == v ? 3 : -1;
}

// All live tets incident to v (empty when v is in no tet).
void vertexStar(const TetMesh& mesh, VertexTetIndex& index, VertexId v, std::vector<TetId>& star);

// The live tets incident to v, by adjacency from t (which contains v). Marks visited tets
// with scratch bit 2 and clears it again; without marks (`marked` false: a side of MeshHalves,
// where the other side may read the flags of shared tets) a list search tells the visited
// ones instead, in the same order (stars hold tens of tets).
inline void starOf(TetMesh& mesh, TetId t, VertexId v, std::vector<TetId>& star, bool marked = true)
{
  constexpr std::uint8_t kSeen = kScratchBit2;
  star.clear();
  star.push_back(t);
  if (marked)
    mesh.flags[t] |= kSeen;
  for (std::size_t i = 0; i < star.size(); ++i)
  {
    const TetId u = star[i];
    for (int f = 0; f < 4; ++f)
    {
      if (mesh.vertex(u, f) == v)
        continue; // the face opposite v does not contain v
      const FaceRef n = mesh.neighbor(u, f);
      if (n == kNoNeighbor)
        continue;
      const TetId w = faceTet(n);
      if (marked ? !(mesh.flags[w] & kSeen) : std::find(star.begin(), star.end(), w) == star.end())
      {
        if (marked)
          mesh.flags[w] |= kSeen;
        star.push_back(w);
      }
    }
  }
  if (marked)
    for (TetId u : star)
      mesh.flags[u] = static_cast<std::uint8_t>(mesh.flags[u] & ~kSeen);
}

// A tet having edge (a,b), or -1.
TetId findEdge(const TetMesh& mesh, VertexTetIndex& index, VertexId a, VertexId b);

// A face ref 4*t+f of a tet face with vertices {a,b,c}, or -1.
FaceRef findFace(const TetMesh& mesh, VertexTetIndex& index, VertexId a, VertexId b, VertexId c);

// The tets around edge (p,q), starting at tet t (which must contain the edge), in order, and
// the ring of opposite vertices: shell[k] = (p, q, ring[k], ring[k+1]) up to an even
// permutation (so orient3d(p, q, ring[k], ring[k+1]) > 0). Returns false when the edge lies
// on the hull (open shell).
bool edgeShell(const TetMesh& mesh,
  TetId t,
  VertexId p,
  VertexId q,
  std::vector<TetId>& shell,
  std::vector<VertexId>& ring);

// Replaces the live tets `oldTets` by `newTets` (positively oriented, covering exactly the
// same region). Faces shared with the rest of the mesh are glued back with their constraint
// flags; faces between two new tets are glued to each other. The new tets' ids go to
// `created` when given (to undo: replace them by the old vertex quadruples). With `pool`,
// the old slots go to it and the new tets come from it (it must have newTets.size() -
// oldTets.size() slots available); else the mesh's free list and its end are used.
void replaceTets(TetMesh& mesh,
  VertexTetIndex& index,
  const std::vector<TetId>& oldTets,
  const std::vector<TetVertices>& newTets,
  std::vector<TetId>* created = nullptr,
  TetSlotPool* pool = nullptr);

} // namespace tetmesher
