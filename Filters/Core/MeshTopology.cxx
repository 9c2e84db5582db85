#include "MeshTopology.h"

#include "SurfaceInput.h"

#include <algorithm>
#include <cassert>

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

void VertexTetIndex::note(TetId t, const TetMesh& mesh)
{
  if (static_cast<VertexId>(vertexTet_.size()) < mesh.vertexCount())
    vertexTet_.resize(mesh.vertexCount(), -1);
  for (int i = 0; i < 4; ++i)
    vertexTet_[mesh.vertex(t, i)] = t;
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

void vertexStar(const TetMesh& mesh, VertexTetIndex& index, VertexId v, std::vector<TetId>& star)
{
  star.clear();
  TetId start = index.tetOf(mesh, v);
  if (start < 0)
    return;
  index.startVisit();
  index.visit(start);
  star.push_back(start);
  for (std::size_t k = 0; k < star.size(); ++k)
  {
    TetId t = star[k];
    int iv = localIndex(mesh, t, v);
    for (int f = 0; f < 4; ++f)
    {
      FaceRef n = mesh.neighbor(t, f);
      if (f == iv || n == kNoNeighbor)
        continue;
      TetId u = faceTet(n);
      if (index.visit(u))
        star.push_back(u);
    }
  }
}

namespace
{
// Walks the star of a in the order of vertexStar and returns the first tet for which
// `match` is true (or -1), without building the whole star.
template<typename Match>
TetId firstInStar(const TetMesh& mesh, VertexTetIndex& index, VertexId a, Match match)
{
  TetId start = index.tetOf(mesh, a);
  if (start < 0)
    return -1;
  thread_local std::vector<TetId> queue;
  queue.clear();
  index.startVisit();
  index.visit(start);
  queue.push_back(start);
  for (std::size_t k = 0; k < queue.size(); ++k)
  {
    TetId t = queue[k];
    if (match(t))
      return t;
    int ia = localIndex(mesh, t, a);
    for (int f = 0; f < 4; ++f)
    {
      FaceRef n = mesh.neighbor(t, f);
      if (f == ia || n == kNoNeighbor)
        continue;
      TetId u = faceTet(n);
      if (index.visit(u))
        queue.push_back(u);
    }
  }
  return -1;
}
} // namespace

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
  std::vector<TetId>* created)
{
  if (created)
    created->clear();
  struct BoundaryFace
  {
    std::array<VertexId, 3> key;
    FaceRef outside;
    bool constrained;
  };
  // Element-wise (std::array's == becomes a memcmp call here, the hot spot of this loop).
  auto same = [](const std::array<VertexId, 3>& x, const std::array<VertexId, 3>& y)
  { return x[0] == y[0] && x[1] == y[1] && x[2] == y[2]; };
  // Scratch kept between calls: recovery and optimisation call this for every move.
  thread_local std::vector<BoundaryFace> boundary;
  boundary.clear();
  for (TetId t : oldTets)
  {
    for (int f = 0; f < 4; ++f)
    {
      FaceRef n = mesh.neighbor(t, f);
      if (n != kNoNeighbor &&
        std::find(oldTets.begin(), oldTets.end(), faceTet(n)) != oldTets.end())
        continue;
      const int* fv = kFaceVertices[f];
      boundary.push_back(
        { sortedTriangle(mesh.vertex(t, fv[0]), mesh.vertex(t, fv[1]), mesh.vertex(t, fv[2])),
          n,
          mesh.isConstrained(t, f) });
    }
  }
  for (TetId t : oldTets)
    mesh.deleteTet(t);

  struct OpenFace
  {
    std::array<VertexId, 3> key;
    TetId tet;
    int face;
  };
  thread_local std::vector<OpenFace> open;
  open.clear();
  for (const TetVertices& v : newTets)
  {
    TetId t = mesh.addTet(v[0], v[1], v[2], v[3]);
    index.note(t, mesh);
    if (created)
      created->push_back(t);
    for (int f = 0; f < 4; ++f)
    {
      const int* fv = kFaceVertices[f];
      auto key = sortedTriangle(v[fv[0]], v[fv[1]], v[fv[2]]);
      auto b = std::find_if(
        boundary.begin(), boundary.end(), [&](const BoundaryFace& x) { return same(x.key, key); });
      if (b != boundary.end())
      {
        if (b->outside == kNoNeighbor)
          mesh.setHull(t, f);
        else
          mesh.glue(t, f, faceTet(b->outside), faceIndex(b->outside));
        mesh.setConstrained(t, f, b->constrained);
        continue;
      }
      auto o =
        std::find_if(open.begin(), open.end(), [&](const OpenFace& x) { return same(x.key, key); });
      if (o != open.end())
      {
        mesh.glue(t, f, o->tet, o->face);
        open.erase(o);
      }
      else
        open.push_back({ key, t, f });
    }
  }
  assert(open.empty());
}

} // namespace tetmesher
