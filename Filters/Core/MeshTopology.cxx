#include "MeshTopology.h"

#include "SurfaceInput.h"

#include <algorithm>
#include <cassert>
#include <cstdint>

namespace tetmesher
{

void VertexTetIndex::rebuild(const TetMesh& mesh)
{
  // The last live tet of each vertex, as note() in id order gives; written directly (this
  // runs after every recovery Steiner point, over the whole mesh).
  vertexTet_.assign(mesh.vertexCount(), -1);
  const VertexId* tets = mesh.tets.data();
  const TetId count = mesh.tetCapacity();
  for (TetId t = 0; t < count; ++t, tets += 4)
  {
    if (tets[0] == kDeletedTet)
      continue;
    for (int i = 0; i < 4; ++i)
      vertexTet_[tets[i]] = t;
  }
}

TetId VertexTetIndex::tetOf(const TetMesh& mesh, VertexId v)
{
  auto valid = [&](TetId t)
  { return t >= 0 && t < mesh.tetCapacity() && !mesh.isDeleted(t) && localIndex(mesh, t, v) >= 0; };
  if (v < static_cast<VertexId>(vertexTet_.size()) && valid(vertexTet_[v]))
    return vertexTet_[v];
  rebuild(mesh);
  return vertexTet_[v];
}

void VertexTetIndex::resetStamps()
{
  std::fill(stamp_.begin(), stamp_.end(), 0u);
  epoch_ = 1;
}

namespace
{
// Walks the star of v by adjacency from index.tetOf(v), breadth first, appending its tets to
// `queue` (cleared first), and returns the first for which `stop` is true (-1: none, the
// whole star then in `queue`). Only faces with v are read: the optimiser's halves of space
// (QualityOptimization.cxx) may meanwhile re-glue the face opposite v when v is on the other
// side.
template<typename Stop>
TetId walkStar(const TetMesh& mesh,
  VertexTetIndex& index,
  VertexId v,
  std::vector<TetId>& queue,
  Stop stop)
{
  queue.clear();
  const TetId start = index.tetOf(mesh, v);
  if (start < 0)
    return -1;
  index.startVisit();
  index.visit(start);
  queue.push_back(start);
  for (std::size_t k = 0; k < queue.size(); ++k)
  {
    const TetId t = queue[k];
    if (stop(t))
      return t;
    const int iv = localIndex(mesh, t, v);
    for (int f = 0; f < 4; ++f)
    {
      if (f == iv)
        continue;
      const FaceRef n = mesh.neighbor(t, f);
      if (n == kNoNeighbor)
        continue;
      const TetId u = faceTet(n);
      if (index.visit(u))
        queue.push_back(u);
    }
  }
  return -1;
}

// The first tet of a's star, in vertexStar's order, for which `match` is true (or -1),
// without building the rest of the star.
template<typename Match>
TetId firstInStar(const TetMesh& mesh, VertexTetIndex& index, VertexId a, Match match)
{
  thread_local std::vector<TetId> queue;
  return walkStar(mesh, index, a, queue, match);
}
} // namespace

void vertexStar(const TetMesh& mesh, VertexTetIndex& index, VertexId v, std::vector<TetId>& star)
{
  walkStar(mesh, index, v, star, [](TetId) { return false; });
}

TetId findEdge(const TetMesh& mesh, VertexTetIndex& index, VertexId a, VertexId b)
{
  return firstInStar(mesh, index, a, [&](TetId t) { return localIndex(mesh, t, b) >= 0; });
}

FaceRef findFace(const TetMesh& mesh, VertexTetIndex& index, VertexId a, VertexId b, VertexId c)
{
  TetId t = firstInStar(mesh,
    index,
    a,
    [&](TetId u) { return localIndex(mesh, u, b) >= 0 && localIndex(mesh, u, c) >= 0; });
  if (t < 0)
    return -1;
  for (int f = 0; f < 4; ++f)
  {
    VertexId w = mesh.vertex(t, f);
    if (w != a && w != b && w != c)
      return makeFaceRef(t, f);
  }
  return -1;
}

namespace
{
// True when (i0,i1,i2,i3) is an even permutation of (0,1,2,3).
bool evenPermutation(int i0, int i1, int i2, int i3)
{
  int p[4] = { i0, i1, i2, i3 };
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      inversions += p[i] > p[j];
  return inversions % 2 == 0;
}
} // namespace

bool edgeShell(const TetMesh& mesh,
  TetId t,
  VertexId p,
  VertexId q,
  std::vector<TetId>& shell,
  std::vector<VertexId>& ring)
{
  shell.clear();
  ring.clear();
  // Defensive: callers pass a live tet with the edge, and a consistent mesh keeps it along the
  // walk. Recovery of self-intersecting input (validateInput off) breaks that (a fuzzer input,
  // Testing/Fuzz/regressions/unchecked-self-intersection-adjacency.bin); without these checks
  // the walk reads outside the arrays.
  if (t < 0 || t >= mesh.tetCapacity() || mesh.isDeleted(t))
    return false;
  TetId start = t;
  int ip = localIndex(mesh, t, p);
  int iq = localIndex(mesh, t, q);
  if (ip < 0 || iq < 0 || ip == iq)
    return false;
  int i = 0;
  while (i == ip || i == iq)
    ++i;
  int j = 6 - ip - iq - i;
  if (!evenPermutation(ip, iq, i, j))
    std::swap(i, j);
  ring.push_back(mesh.vertex(t, i));
  while (true)
  {
    shell.push_back(t);
    // (p, q, ring.back(), next) is positive; step across the face opposite ring.back().
    VertexId next = mesh.vertex(t, j);
    FaceRef n = mesh.neighbor(t, i);
    if (n == kNoNeighbor)
      return false;
    TetId u = faceTet(n);
    if (u == start)
      return true;
    if (shell.size() > 1000)
      return false; // corrupt mesh guard
    ring.push_back(next);
    // In u: the vertex opposite the shared face is the next ring vertex.
    ip = localIndex(mesh, u, p);
    iq = localIndex(mesh, u, q);
    i = localIndex(mesh, u, next);
    if (ip < 0 || iq < 0 || i < 0)
      return false;
    j = 6 - ip - iq - i;
    t = u;
  }
}

void replaceTets(TetMesh& mesh,
  VertexTetIndex& index,
  const std::vector<TetId>& oldTets,
  const std::vector<TetVertices>& newTets,
  std::vector<TetId>* created,
  TetSlotPool* pool)
{
  if (created)
    created->clear();
  // The faces of the region (boundary: the old tets' faces that stay, with what lies across
  // them) and the new tets' faces not yet glued (open), matched by their sorted vertices in a
  // small hash table: a linear search per new face was most of this function's time, which
  // recovery and optimisation spend on every move, made or undone. A boundary face matches
  // before an open one, and the first of equal boundary faces wins, as a linear search would
  // (equal faces only arise on broken meshes, e.g. unchecked self-intersecting input).
  // The faces live in the slots, which an epoch empties: no clearing and no indirection per
  // call (this runs for every move, and undo, of the flip searches).
  struct Slot
  {
    VertexId key[3];
    FaceRef outside;         // boundary: the face across (or kNoNeighbor); open: makeFaceRef(t, f)
    std::uint32_t epoch = 0; // in use when equal to the call's epoch
    bool boundary;
    bool constrained; // boundary only
  };
  thread_local std::vector<Slot> slots;
  thread_local std::uint32_t epoch = 0;
  std::size_t size = 16;
  while (size < 2 * 4 * (oldTets.size() + newTets.size()))
    size *= 2;
  if (slots.size() < size)
    slots.resize(size);
  if (++epoch == 0)
  {
    for (Slot& slot : slots)
      slot.epoch = 0;
    epoch = 1;
  }
  const std::uint32_t now = epoch;
  const std::size_t mask = size - 1;
  // The slot of face (a,b,c): the one holding it, else the empty one where it would go.
  auto slotOf = [&](VertexId a, VertexId b, VertexId c) -> Slot&
  {
    const std::array<VertexId, 3> key = sortedTriangle(a, b, c);
    std::uint64_t h = static_cast<std::uint32_t>(key[0]) * 0x9e3779b97f4a7c15ull ^
      static_cast<std::uint32_t>(key[1]) * 0xc2b2ae3d27d4eb4full ^
      static_cast<std::uint32_t>(key[2]) * 0x165667b19e3779f9ull;
    for (std::size_t i = (h ^ (h >> 29)) & mask;; i = (i + 1) & mask)
    {
      Slot& slot = slots[i];
      if (slot.epoch != now)
      {
        std::copy(key.begin(), key.end(), slot.key);
        return slot;
      }
      if (slot.key[0] == key[0] && slot.key[1] == key[1] && slot.key[2] == key[2])
        return slot;
    }
  };
  for (TetId t : oldTets)
  {
    const VertexId* v = &mesh.tets[4 * static_cast<std::size_t>(t)];
    for (int f = 0; f < 4; ++f)
    {
      // A neighbour in the region: not a boundary face. (A search of the few old tets, not a
      // mark per tet slot: such an array grew with the mesh, +9 MB at fandisk h/2.)
      FaceRef n = mesh.neighbor(t, f);
      if (n != kNoNeighbor &&
        std::find(oldTets.begin(), oldTets.end(), faceTet(n)) != oldTets.end())
        continue;
      const int* fv = kFaceVertices[f];
      Slot& slot = slotOf(v[fv[0]], v[fv[1]], v[fv[2]]);
      if (slot.epoch != now)
      {
        slot.epoch = now;
        slot.outside = n;
        slot.boundary = true;
        slot.constrained = mesh.isConstrained(t, f);
      }
    }
  }
  for (TetId t : oldTets)
    if (pool)
      mesh.deleteTet(*pool, t);
    else
      mesh.deleteTet(t);

  std::size_t openCount = 0;
  for (const TetVertices& v : newTets)
  {
    TetId t =
      pool ? mesh.addTet(*pool, v[0], v[1], v[2], v[3]) : mesh.addTet(v[0], v[1], v[2], v[3]);
    index.note(t, mesh);
    if (created)
      created->push_back(t);
    for (int f = 0; f < 4; ++f)
    {
      const int* fv = kFaceVertices[f];
      Slot& slot = slotOf(v[fv[0]], v[fv[1]], v[fv[2]]);
      if (slot.epoch != now)
      {
        slot.epoch = now;
        slot.outside = makeFaceRef(t, f);
        slot.boundary = false;
        ++openCount;
      }
      else if (slot.boundary)
      {
        if (slot.outside == kNoNeighbor)
          mesh.setHull(t, f);
        else
          mesh.glue(t, f, faceTet(slot.outside), faceIndex(slot.outside));
        mesh.setConstrained(t, f, slot.constrained);
      }
      else if (slot.outside != kNoNeighbor)
      {
        mesh.glue(t, f, faceTet(slot.outside), faceIndex(slot.outside));
        slot.outside = kNoNeighbor; // glued: the slot stays, free for a later equal face
        --openCount;
      }
      else
      {
        slot.outside = makeFaceRef(t, f);
        ++openCount;
      }
    }
  }
  assert(openCount == 0);
  (void)openCount;
}

} // namespace tetmesher
