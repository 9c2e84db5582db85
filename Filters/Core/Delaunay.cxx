// Incremental Delaunay insertion (Bowyer-Watson) in a box, George-Hecht-Saltel 1990 §2.
//
// Insertion of a point p:
//  1. locate: a visibility walk from a hint tet, crossing a face that p sees negatively
//     (exact orient3d). Faces are tried from a pseudo-random rotating start, which makes the
//     walk terminate with probability 1 even in non-Delaunay meshes (Devillers, Pion,
//     Teillaud 2002); a step limit falls back to an exhaustive scan, so it always terminates.
//  2. cavity: grown by adjacency from the located tet, over tets whose circumsphere contains
//     p (insphereSoS > 0), never across a constrained face.
//  3. (checked mode, used by insertVertex) the cavity is shrunk until p sees every cavity
//     boundary face strictly positively and no vertex is enclosed, which is automatic for
//     a Delaunay mesh but not after boundary recovery has flipped or constrained it.
//  4. the cavity tets are replaced by the cones (boundary face, p), reusing the cavity's
//     slots first. Internal faces of the cone are glued through a table of their edges:
//     indexed by local numbers of the boundary vertices (fast mode, up to 64 of them), else
//     a small hash table.
//
// Partitioned insertion (buildDelaunay, large BRIO rounds; after the parallel Delaunay of
// Gmsh HXT, Marot, Pellerin and Remacle 2019, with two fixed halves): a round's points are
// split at the median of their longest extent, and each half is inserted by its own thread.
// A tet belongs to a side when its 4 vertices lie in that side's half; a side only deletes
// and creates its own tets (a cone over a face of its own tets is its own), and postpones a
// point whose walk or cavity would reach a tet with a vertex of the other half. The halves
// then split again across the first split for the postponed points, and the rest go in
// order. Each side reads only data the other never writes, so the mesh, tet numbering
// included, is the same on one thread or two.
//
// Checked mode (insertVertex) uses scratch flag bits, cleared before returning: kScratchBit0 =
// tet is in the cavity, kScratchBit1 = tet was tested and is not in the cavity. Fast mode
// (buildDelaunay, no constraints) never touches mesh.flags: it marks tets in the sign bits of
// their vertex ids (see growCavityFast), also cleared before the insertion returns.
#include "Delaunay.h"

#include "FilteredPredicates.h"
#include "HilbertSort.h"
#include "HugePages.h"
#include "MedianSplit.h"
#include "MeshValidation.h"
#include "ParallelPair.h"
#include "Predicates.h"
#include "SmallLattice.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <memory>

namespace tetmesher
{

namespace
{
// Fixed seed of the walk's face-choice generator: walks, hence meshes, are deterministic.
constexpr std::uint64_t kWalkSeed = 0x2545F4914F6CDD1DULL;

// xorshift64: the walk only needs a cheap, well-spread choice among four faces.
inline unsigned nextRandom(std::uint64_t& state)
{
  state ^= state << 13;
  state ^= state >> 7;
  state ^= state << 17;
  return static_cast<unsigned>(state >> 32);
}
} // namespace

// Partitioned insertion (insertImpl<.., true>): the half of space one side owns, a coordinate below
// a split value or not. A tet is the side's when its 4 vertices are; only that side creates or
// deletes such tets, so two sides never touch the same tet (see insertImpl).
struct SpacePartition
{
  const double* coords;
  int axis;
  double split;
  bool lower; // owns the vertices whose coordinate is below split

  bool owns(VertexId v) const
  {
    return (coords[3 * static_cast<std::size_t>(v) + axis] < split) == lower;
  }
  // The tet's 4 vertex ids (without marks) are all the side's.
  bool ownsTet(const VertexId* tv) const
  {
    return owns(tv[0]) && owns(tv[1]) && owns(tv[2]) && owns(tv[3]);
  }
};

// The tet slots one side may fill: slots it freed, then a private range of the arrays.
struct SlotPool
{
  std::vector<TetId> freed;
  TetId next = 0, end = 0;

  std::size_t available() const { return freed.size() + static_cast<std::size_t>(end - next); }
  TetId take()
  {
    if (freed.empty())
      return next++;
    const TetId t = freed.back();
    freed.pop_back();
    return t;
  }
};

struct InsertionWorkspace
{
  struct BoundaryFace
  {
    VertexId v[3];    // outward from the cavity
    FaceRef outside;  // the face of the tet beyond, or kNoNeighbor
    bool constrained; // constrained flag carried over to the new tet
  };
  // Slot of the edge table that glues the cone's tets: a directed boundary edge, the face of
  // the new tet that contains it, and the insertion it belongs to (stale slots are empty,
  // so the table never needs clearing).
  struct EdgeSlot
  {
    std::uint32_t stamp;
    VertexId from, to;
    FaceRef face;
  };

  // Sized ahead and filled by index in fast mode (growCavityFast).
  FlatArray<TetId> cavity;
  FlatArray<TetId> rejected;
  std::vector<TetId> cone; // directed gluing: the new tet of each boundary face
  // Checked mode: a constrained face has the cavity on both sides (the cavity reached around
  // it), so its edges are on more than two boundary faces and fillCavity glues pairwise.
  bool internalConstraint = false;
  FlatArray<BoundaryFace> boundary;
  std::vector<EdgeSlot> edgeTable = std::vector<EdgeSlot>(512, EdgeSlot{ 0, -1, -1, 0 });
  std::uint32_t edgeStamp = 0;
  // Fast mode's gluing by local vertex numbers: each boundary vertex of the cavity gets a
  // number below kMaxLocal (vertexTag: insertion epoch << 8 | number), and the directed edge
  // (i, j) its cone face at localEdges[i * kMaxLocal + j]. Cavities with more boundary
  // vertices use edgeTable.
  static constexpr int kMaxLocal = 64;
  std::vector<std::uint32_t> vertexTag;
  std::uint32_t tagEpoch = 0;
  std::vector<std::uint8_t> faceLocal; // 3 per boundary face
  std::vector<FaceRef> localEdges = std::vector<FaceRef>(kMaxLocal * kMaxLocal);
  std::vector<std::uint32_t> vertexStamp; // checked mode only
  std::uint32_t stamp = 0;
  std::uint64_t rng = kWalkSeed;
  // Ids that define the symbolic perturbation, when the mesh being built uses other ids
  // (buildDelaunay renumbers the points in insertion order); nullptr: the ids themselves.
  const VertexId* perturbationIds = nullptr;
  // Vertices below this id lie on one small lattice (SmallLattice.h): in-sphere tests among
  // them are exact in doubles. 0: none (buildDelaunay sets it for its input points alone).
  VertexId smallLatticeVertices = 0;
  // Partitioned insertion only: the side this workspace inserts for, and its slots.
  const SpacePartition* partition = nullptr;
  SlotPool* pool = nullptr;

  InsertionWorkspace()
  {
    cavity.reserve(256);
    rejected.reserve(256);
    boundary.reserve(512);
  }
};

InsertionWorkspace* createInsertionWorkspace()
{
  return new InsertionWorkspace;
}
void destroyInsertionWorkspace(InsertionWorkspace* workspace)
{
  delete workspace;
}

namespace
{

constexpr std::uint8_t kInCavity = kScratchBit0;
constexpr std::uint8_t kRejected = kScratchBit1;

inline const double* pointOf(const double* coords, VertexId v)
{
  return coords + 3 * static_cast<std::size_t>(v);
}

// The perturbed in-sphere test of the insertion: by the small-lattice evaluation when all five
// points are on the input's lattice, else filtered with the exact fallback (the same answers).
// Forced inline: GCC otherwise calls it out of line in MeshHalves::insert (16% of the lattice
// insertion's samples on fandisk at h/2).
__attribute__((always_inline)) inline int insphereOf(const InsertionWorkspace& ws,
  const double* coords,
  VertexId a,
  VertexId b,
  VertexId c,
  VertexId d,
  VertexId e)
{
  // The common case, no lattice, by one comparison rather than a maximum of five ids.
  if (ws.smallLatticeVertices > 0 && std::max({ a, b, c, d, e }) < ws.smallLatticeVertices)
    return predicates::insphereSoSSmallLattice(coords, a, b, c, d, e, ws.perturbationIds);
  return predicates::insphereSoSFiltered(coords, a, b, c, d, e, ws.perturbationIds);
}

// orient3d of face f of tet t (outward vertex order) with p: > 0 when p is on the inner side.
inline int faceOrient(const TetMesh& mesh, const double* coords, TetId t, int f, const double* p)
{
  const VertexId* tv = &mesh.tets[4 * static_cast<std::size_t>(t)];
  return predicates::orient3dFiltered(pointOf(coords, tv[kFaceVertices[f][0]]),
    pointOf(coords, tv[kFaceVertices[f][1]]),
    pointOf(coords, tv[kFaceVertices[f][2]]),
    p);
}

// faceOrient, evaluated as on a small lattice (SmallLattice.h) when the face's vertices are
// below `smallLatticeVertices` (p must then be on the lattice too).
inline int faceOrientOf(const TetMesh& mesh,
  const double* coords,
  TetId t,
  int f,
  const double* p,
  VertexId smallLatticeVertices)
{
  const VertexId* tv = &mesh.tets[4 * static_cast<std::size_t>(t)];
  const VertexId a = tv[kFaceVertices[f][0]], b = tv[kFaceVertices[f][1]],
                 c = tv[kFaceVertices[f][2]];
  if (smallLatticeVertices > 0 && std::max({ a, b, c }) < smallLatticeVertices)
    return predicates::orient3dSmallLattice(
      pointOf(coords, a), pointOf(coords, b), pointOf(coords, c), p);
  return predicates::orient3dFiltered(
    pointOf(coords, a), pointOf(coords, b), pointOf(coords, c), p);
}

inline bool faceConstrained(const TetMesh& mesh, TetId t, int f)
{
  if (mesh.flags[t] & (1u << f))
    return true;
  const FaceRef n = mesh.neighbor(t, f);
  return n != kNoNeighbor && (mesh.flags[faceTet(n)] & (1u << faceIndex(n)));
}

bool closureContains(const TetMesh& mesh, const double* coords, TetId t, const double* p)
{
  for (int f = 0; f < 4; ++f)
    if (faceOrient(mesh, coords, t, f, p) < 0)
      return false;
  return true;
}

TetId exhaustiveLocate(const TetMesh& mesh, const double* p)
{
  const double* coords = mesh.coords.data();
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (!mesh.isDeleted(t) && closureContains(mesh, coords, t, p))
      return t;
  return -1;
}

// walk's answer when a partitioned walk would have to leave its side's tets.
constexpr TetId kPostponed = -2;

// Partitioned: the walk never crosses a face whose 3 vertices all belong to the other side
// (the other side may be rewriting the tets there); it returns kPostponed instead, and on
// reaching the step limit. smallLatticeVertices: as in InsertionWorkspace, when p is on the
// lattice (0 otherwise).
template<bool Partitioned = false>
TetId walk(const TetMesh& mesh,
  const double* p,
  TetId start,
  std::uint64_t& rng,
  const SpacePartition* side = nullptr,
  VertexId smallLatticeVertices = 0)
{
  const double* coords = mesh.coords.data();
  TetId t = start;
  int enteredBy = -1;
  const std::size_t limit = 64 + 4 * static_cast<std::size_t>(mesh.liveTetCount());
  for (std::size_t steps = 0; steps < limit; ++steps)
  {
    const unsigned r = nextRandom(rng);
    bool moved = false;
    for (int i = 0; i < 4; ++i)
    {
      const int f = static_cast<int>((r + i) & 3u);
      if (f == enteredBy) // p is known to be strictly on the inner side of this face
        continue;
      if (faceOrientOf(mesh, coords, t, f, p, smallLatticeVertices) < 0)
      {
        if constexpr (Partitioned)
        {
          const VertexId* tv = &mesh.tets[4 * static_cast<std::size_t>(t)];
          if (!side->owns(tv[kFaceVertices[f][0]]) && !side->owns(tv[kFaceVertices[f][1]]) &&
            !side->owns(tv[kFaceVertices[f][2]]))
            return kPostponed;
        }
        const FaceRef n = mesh.neighbor(t, f);
        if (n == kNoNeighbor)
          return -1;
        t = faceTet(n);
        enteredBy = faceIndex(n);
        moved = true;
        break;
      }
    }
    if (!moved)
      return t;
  }
  if constexpr (Partitioned)
    return kPostponed;
  return exhaustiveLocate(mesh, p);
}

void removeFromCavity(TetMesh& mesh, InsertionWorkspace& ws, TetId t)
{
  mesh.flags[t] = static_cast<std::uint8_t>((mesh.flags[t] & ~kInCavity) | kRejected);
  ws.rejected.push_back(t);
}

void clearMarks(TetMesh& mesh, InsertionWorkspace& ws)
{
  for (TetId t : ws.cavity)
    mesh.flags[t] = static_cast<std::uint8_t>(mesh.flags[t] & ~(kInCavity | kRejected));
  for (TetId t : ws.rejected)
    mesh.flags[t] = static_cast<std::uint8_t>(mesh.flags[t] & ~(kInCavity | kRejected));
}

enum class ShrinkOutcome
{
  Ok,
  OnConstraint
};

// Checked mode: removes cavity tets until the cavity is a star around p whose boundary faces
// p sees strictly positively, that crosses no constrained face, and that encloses no vertex.
// Tets whose closure contains p can never be removed; needing to is "p is on a constraint".
ShrinkOutcome shrinkToStar(TetMesh& mesh, const double* p, TetId start, InsertionWorkspace& ws)
{
  const double* coords = mesh.coords.data();
  auto inCavity = [&mesh](TetId u) { return (mesh.flags[u] & kInCavity) != 0; };
  auto tryRemove = [&](TetId c) -> bool
  {
    if (c == start || closureContains(mesh, coords, c, p))
      return false;
    removeFromCavity(mesh, ws, c);
    return true;
  };
  for (;;)
  {
    bool changed = false;
    for (std::size_t i = 0; i < ws.cavity.size(); ++i)
    {
      const TetId c = ws.cavity[i];
      if (!inCavity(c))
        continue;
      for (int f = 0; f < 4; ++f)
      {
        const FaceRef n = mesh.neighbor(c, f);
        const bool constrained = faceConstrained(mesh, c, f);
        const bool outsideInCavity = n != kNoNeighbor && inCavity(faceTet(n));
        if (outsideInCavity && !constrained)
          continue; // internal face
        if (faceOrient(mesh, coords, c, f, p) > 0)
          continue; // a visible boundary face (or a constrained face p sees from inside c)
        // p does not see face f from inside c: c must go.
        if (!tryRemove(c))
          return ShrinkOutcome::OnConstraint;
        changed = true;
        break;
      }
    }
    if (!changed)
    {
      // No vertex may be swallowed: every vertex of a cavity tet must lie on its boundary.
      if (ws.vertexStamp.size() < static_cast<std::size_t>(mesh.vertexCount()))
        ws.vertexStamp.resize(static_cast<std::size_t>(mesh.vertexCount()) + 1024, 0);
      if (++ws.stamp == 0)
      {
        std::fill(ws.vertexStamp.begin(), ws.vertexStamp.end(), 0);
        ws.stamp = 1;
      }
      for (TetId c : ws.cavity)
        if (inCavity(c))
          for (int f = 0; f < 4; ++f)
          {
            const FaceRef n = mesh.neighbor(c, f);
            if (n == kNoNeighbor || !inCavity(faceTet(n)) || faceConstrained(mesh, c, f))
              for (int k = 0; k < 3; ++k)
                ws.vertexStamp[static_cast<std::size_t>(mesh.vertex(c, kFaceVertices[f][k]))] =
                  ws.stamp;
          }
      for (std::size_t i = 0; i < ws.cavity.size(); ++i)
      {
        const TetId c = ws.cavity[i];
        if (!inCavity(c))
          continue;
        for (int k = 0; k < 4; ++k)
          if (ws.vertexStamp[static_cast<std::size_t>(mesh.vertex(c, k))] != ws.stamp)
          {
            if (!tryRemove(c))
              return ShrinkOutcome::OnConstraint;
            changed = true;
            break;
          }
      }
    }
    if (!changed)
      break;
  }
  // Compact the cavity list.
  std::size_t kept = 0;
  for (TetId c : ws.cavity)
    if (inCavity(c))
      ws.cavity[kept++] = c;
  ws.cavity.resize(kept);
  return ShrinkOutcome::Ok;
}

// Fills ws.boundary from the (final) cavity.
void collectBoundary(TetMesh& mesh, InsertionWorkspace& ws)
{
  ws.boundary.clear();
  for (TetId c : ws.cavity)
  {
    const VertexId* tv = &mesh.tets[4 * static_cast<std::size_t>(c)];
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = mesh.neighbor(c, f);
      const bool constrained = faceConstrained(mesh, c, f);
      if (n != kNoNeighbor && (mesh.flags[faceTet(n)] & kInCavity) && !constrained)
        continue;
      ws.boundary.push_back(
        { { tv[kFaceVertices[f][0]], tv[kFaceVertices[f][1]], tv[kFaceVertices[f][2]] },
          n,
          constrained });
    }
  }
}

// Fast mode's marks live in the sign bits of a tet's own vertex ids (ids are non-negative):
// the tet's vertices are loaded anyway to test it, so the mark costs no extra cache miss,
// where mesh.flags or a side table would. Bit 31 of vertex 3: tested; of vertex 2: in the
// cavity. Cavity tets are overwritten by fillCavity, rejected ones unmarked after the search.
constexpr std::uint32_t kMarkBit = 0x80000000u;

inline bool hasMark(const VertexId* tv, int k)
{
  return (static_cast<std::uint32_t>(tv[k]) & kMarkBit) != 0;
}

inline void setMark(VertexId* tv, int k)
{
  tv[k] = static_cast<VertexId>(static_cast<std::uint32_t>(tv[k]) | kMarkBit);
}

inline VertexId unmarked(VertexId v)
{
  return static_cast<VertexId>(static_cast<std::uint32_t>(v) & ~kMarkBit);
}

inline void unmarkCavity(VertexId* tets, const InsertionWorkspace& ws)
{
  for (TetId c : ws.cavity)
  {
    VertexId* cv = tets + 4 * static_cast<std::size_t>(c);
    cv[2] = unmarked(cv[2]);
    cv[3] = unmarked(cv[3]);
  }
  for (TetId r : ws.rejected)
  {
    VertexId* rv = tets + 4 * static_cast<std::size_t>(r);
    rv[3] = unmarked(rv[3]);
  }
}

// Fast mode (buildDelaunay only): the mesh has no constrained faces, so mesh.flags is never
// read. The boundary is recorded on the fly. Same breadth-first order as the checked version,
// hence the same tet ids.
// Partitioned (start is a tet of ws.partition's side): a neighbour that is not the side's
// own (it has a vertex of the other side) is tested without a mark, since the other side may
// read it; if it is in conflict the cavity would cross into shared tets, so the marks are
// undone and false returned (the point is postponed).
template<bool Partitioned = false>
bool growCavityFast(TetMesh& mesh, VertexId v, TetId start, InsertionWorkspace& ws)
{
  const double* coords = mesh.coords.data();
  const FaceRef* neighbors = mesh.neighbors.data();
  VertexId* tets = mesh.tets.data();
  // The in-sphere outcome is a coin flip, and a mispredicted branch on it waits for the whole
  // test: the lists are written at their counts and the counts advanced by the outcome, so
  // that the tests of one tet's neighbours overlap. Each list has room for four more entries
  // before a tet's faces are read.
  auto& cavity = ws.cavity;
  auto& rejected = ws.rejected;
  auto& boundary = ws.boundary;
  cavity.resize(std::max<std::size_t>(cavity.capacity(), 64));
  rejected.resize(std::max<std::size_t>(rejected.capacity(), 64));
  boundary.resize(std::max<std::size_t>(boundary.capacity(), 64));
  std::size_t cavityCount = 1, rejectedCount = 0, boundaryCount = 0;
  setMark(tets + 4 * static_cast<std::size_t>(start), 3);
  setMark(tets + 4 * static_cast<std::size_t>(start), 2);
  cavity[0] = start;
  for (std::size_t i = 0; i < cavityCount; ++i)
  {
    if (cavity.size() < cavityCount + 4)
      cavity.resize(2 * cavity.size());
    if (rejected.size() < rejectedCount + 4)
      rejected.resize(2 * rejected.size());
    if (boundary.size() < boundaryCount + 4)
      boundary.resize(2 * boundary.size());
    const TetId c = cavity[i];
    const FaceRef* cn = neighbors + 4 * static_cast<std::size_t>(c);
    // Issue the four neighbours' loads together rather than one insphere test apart.
    for (int f = 0; f < 4; ++f)
      if (cn[f] != kNoNeighbor)
        __builtin_prefetch(tets + 4 * static_cast<std::size_t>(faceTet(cn[f])));
    const VertexId* tv = tets + 4 * static_cast<std::size_t>(c);
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = cn[f];
      // The face, written ahead: it is kept when the count moves past it.
      InsertionWorkspace::BoundaryFace& face = boundary[boundaryCount];
      face.v[0] = unmarked(tv[kFaceVertices[f][0]]);
      face.v[1] = unmarked(tv[kFaceVertices[f][1]]);
      face.v[2] = unmarked(tv[kFaceVertices[f][2]]);
      face.outside = n;
      face.constrained = false;
      if (n == kNoNeighbor)
      {
        ++boundaryCount;
        continue;
      }
      const TetId u = faceTet(n);
      VertexId* uv = tets + 4 * static_cast<std::size_t>(u);
      if (hasMark(uv, 2))
        continue; // internal face
      // The new tet glued here will write the outside tet's neighbour entry.
      __builtin_prefetch(neighbors + n, 1);
      if (hasMark(uv, 3))
      {
        ++boundaryCount; // tested before, not in the cavity
        continue;
      }
      // Cavity tets are all the side's, so u's three vertices on the shared face are too:
      // u is the side's iff its apex across the shared face is (one coordinate read instead
      // of four). Not the side's: tested without a mark, since the other side may read it.
      if (Partitioned && !ws.partition->owns(unmarked(uv[faceIndex(n)])))
      {
        if (insphereOf(ws, coords, uv[0], uv[1], uv[2], uv[3], v) > 0)
        {
          cavity.resize(cavityCount);
          rejected.resize(rejectedCount);
          unmarkCavity(tets, ws);
          return false;
        }
        ++boundaryCount;
        continue;
      }
      setMark(uv, 3);
      const bool conflict = insphereOf(ws, coords, uv[0], uv[1], uv[2], unmarked(uv[3]), v) > 0;
      uv[2] = static_cast<VertexId>(
        static_cast<std::uint32_t>(uv[2]) | (static_cast<std::uint32_t>(conflict) << 31));
      cavity[cavityCount] = u;
      rejected[rejectedCount] = u;
      cavityCount += conflict;
      rejectedCount += !conflict;
      boundaryCount += !conflict;
      __builtin_prefetch(neighbors + 4 * static_cast<std::size_t>(u));
    }
  }
  cavity.resize(cavityCount);
  rejected.resize(rejectedCount);
  boundary.resize(boundaryCount);
  for (TetId r : rejected)
  {
    VertexId* rv = tets + 4 * static_cast<std::size_t>(r);
    rv[3] = unmarked(rv[3]);
  }
  return true;
}

// Checked mode: grows the conflict region from `start`, marking tets in mesh.flags and never
// crossing a constrained face. Collects the boundary faces as collectBoundary would (cavity
// order, faces in order) and tests on the way whether v sees each strictly: true when all
// do, the usual case, where shrinkToStar would keep every tet for them.
// Partitioned (start is the side's own): a neighbour with a vertex of the other side is
// tested without a mark; if it is in conflict, the marks are undone and `crossed` set.
template<bool Partitioned = false>
bool growCavityChecked(TetMesh& mesh,
  VertexId v,
  TetId start,
  InsertionWorkspace& ws,
  bool* crossed = nullptr)
{
  const double* coords = mesh.coords.data();
  const double* p = pointOf(coords, v);
  std::uint8_t* flags = mesh.flags.data();
  const FaceRef* neighbors = mesh.neighbors.data();
  const VertexId* tets = mesh.tets.data();
  ws.cavity.clear();
  ws.rejected.clear();
  ws.boundary.clear();
  ws.internalConstraint = false;
  flags[start] |= kInCavity;
  ws.cavity.push_back(start);
  bool allVisible = true;
  for (std::size_t i = 0; i < ws.cavity.size(); ++i)
  {
    const TetId c = ws.cavity[i];
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = neighbors[4 * static_cast<std::size_t>(c) + f];
      bool constrained = (flags[c] >> f) & 1u;
      if (n != kNoNeighbor)
      {
        const TetId u = faceTet(n);
        constrained = constrained || ((flags[u] >> faceIndex(n)) & 1u);
        const VertexId* uv = tets + 4 * static_cast<std::size_t>(u);
        // As in growCavityFast: u is the side's iff its apex across the shared face is.
        if (Partitioned && !constrained && !(flags[u] & (kInCavity | kRejected)) &&
          !ws.partition->owns(uv[faceIndex(n)]))
        {
          // The other side may read this tet: no mark. In conflict, the cavity would cross
          // into it; else its face is a boundary face, below (never kInCavity).
          if (insphereOf(ws, coords, uv[0], uv[1], uv[2], uv[3], v) > 0)
          {
            clearMarks(mesh, ws);
            *crossed = true;
            return false;
          }
        }
        else if (!constrained && !(flags[u] & (kInCavity | kRejected)))
        {
          if (insphereOf(ws, coords, uv[0], uv[1], uv[2], uv[3], v) > 0)
          {
            flags[u] |= kInCavity;
            ws.cavity.push_back(u);
          }
          else
          {
            flags[u] |= kRejected;
            ws.rejected.push_back(u);
          }
        }
        if (flags[u] & kInCavity)
        {
          if (!constrained)
            continue; // an internal face
          ws.internalConstraint = true;
        }
      }
      const VertexId* tv = tets + 4 * static_cast<std::size_t>(c);
      ws.boundary.push_back(
        { { tv[kFaceVertices[f][0]], tv[kFaceVertices[f][1]], tv[kFaceVertices[f][2]] },
          n,
          constrained });
      allVisible = allVisible && faceOrient(mesh, coords, c, f, p) > 0;
    }
  }
  return allVisible;
}

// True when every vertex of a cavity tet is on a boundary face (ws.boundary): none would
// vanish from the mesh. (The check that ends shrinkToStar.)
bool noVertexSwallowed(const TetMesh& mesh, InsertionWorkspace& ws)
{
  if (ws.vertexStamp.size() < static_cast<std::size_t>(mesh.vertexCount()))
    ws.vertexStamp.resize(static_cast<std::size_t>(mesh.vertexCount()) + 1024, 0);
  if (++ws.stamp == 0)
  {
    std::fill(ws.vertexStamp.begin(), ws.vertexStamp.end(), 0);
    ws.stamp = 1;
  }
  for (const auto& face : ws.boundary)
    for (int k = 0; k < 3; ++k)
      ws.vertexStamp[static_cast<std::size_t>(face.v[k])] = ws.stamp;
  for (TetId c : ws.cavity)
    for (int k = 0; k < 4; ++k)
      if (ws.vertexStamp[static_cast<std::size_t>(mesh.vertex(c, k))] != ws.stamp)
        return false;
  return true;
}

// Symmetric in (a, b), so that both directions of an edge probe the same chain. (Not a ^ b:
// after renumbering, nearby vertices have nearby ids and their xors collide constantly.)
inline std::size_t edgeHash(VertexId a, VertexId b, std::size_t mask)
{
  const std::uint64_t lo = static_cast<std::uint32_t>(a < b ? a : b);
  const std::uint64_t hi = static_cast<std::uint32_t>(a < b ? b : a);
  const std::uint64_t h = (lo * 0x9E3779B97F4A7C15ULL) ^ (hi * 0xC2B2AE3D27D4EB4FULL);
  return static_cast<std::size_t>(h >> 40) & mask;
}

// Directed: the two directions of an edge land in different slots (two-pass gluing).
inline std::size_t directedEdgeHash(VertexId from, VertexId to, std::size_t mask)
{
  const std::uint64_t h = (static_cast<std::uint32_t>(from) * 0x9E3779B97F4A7C15ULL) ^
    (static_cast<std::uint32_t>(to) * 0xC2B2AE3D27D4EB4FULL);
  return static_cast<std::size_t>(h >> 40) & mask;
}

// Replaces the cavity by the cone from v over ws.boundary. Returns one of the new tets.
// Fast mode leaves mesh.flags alone: no tet of an unconstrained build has a flag set.
// Partitioned (fast mode): new slots come from ws.pool, whose range the arrays already hold.
template<bool Checked, bool Partitioned = false>
TetId fillCavity(TetMesh& mesh, VertexId v, InsertionWorkspace& ws)
{
  const std::size_t faceCount = ws.boundary.size();
  // Edge table: at most 3*faceCount entries (fast mode stores both directions of each edge);
  // keep the load factor under 1/4.
  if (ws.edgeTable.size() < 12 * faceCount)
  {
    std::size_t size = ws.edgeTable.size();
    while (size < 12 * faceCount)
      size *= 2;
    ws.edgeTable.assign(size, InsertionWorkspace::EdgeSlot{ 0, -1, -1, 0 });
    ws.edgeStamp = 0;
  }
  if (++ws.edgeStamp == 0)
  {
    for (auto& slot : ws.edgeTable)
      slot.stamp = 0;
    ws.edgeStamp = 1;
  }
  const std::uint32_t stamp = ws.edgeStamp;
  const std::size_t mask = ws.edgeTable.size() - 1;
  // Grow the tet arrays by 1/4 when full rather than letting std::vector double them: the
  // arrays are most of the memory, and doubling would cost up to 2x (3x during the copy).
  if (!Partitioned &&
    mesh.freeTets.size() + (mesh.tets.capacity() - mesh.tets.size()) / 4 < faceCount)
  {
    const std::size_t tets = mesh.tets.size() / 4 + faceCount;
    const std::size_t grown = tets + tets / 4;
    mesh.tets.reserve(4 * grown);
    mesh.neighbors.reserve(4 * grown);
    mesh.flags.reserve(grown);
  }

  // Every directed edge is on exactly one boundary face when the cavity's boundary is a
  // sphere: always in fast mode (no constraints), and in checked mode unless a constrained
  // face lies inside the cavity. Then each edge is stored first and looked up second.
  const bool directed = !Checked || !ws.internalConstraint;
  if (directed && ws.cone.size() < faceCount)
    ws.cone.resize(2 * faceCount);
  // Number the boundary vertices (see InsertionWorkspace::localEdges).
  bool local = false;
  if (directed)
  {
    constexpr int kMaxLocal = InsertionWorkspace::kMaxLocal;
    if (ws.vertexTag.size() < static_cast<std::size_t>(mesh.vertexCount()))
      ws.vertexTag.resize(static_cast<std::size_t>(mesh.vertexCount()), 0);
    if (++ws.tagEpoch == (1u << 24))
    {
      std::fill(ws.vertexTag.begin(), ws.vertexTag.end(), 0);
      ws.tagEpoch = 1;
    }
    if (ws.faceLocal.size() < 3 * faceCount)
      ws.faceLocal.resize(6 * faceCount);
    const std::uint32_t epoch = ws.tagEpoch << 8;
    int count = 0;
    local = true;
    for (std::size_t i = 0; i < faceCount && local; ++i)
      for (int e = 0; e < 3; ++e)
      {
        std::uint32_t& tag = ws.vertexTag[static_cast<std::size_t>(ws.boundary[i].v[e])];
        if ((tag & ~0xFFu) != epoch)
        {
          if (count == kMaxLocal)
          {
            local = false;
            break;
          }
          tag = epoch | static_cast<std::uint32_t>(count++);
        }
        ws.faceLocal[3 * i + e] = static_cast<std::uint8_t>(tag & 0xFFu);
      }
  }
  // Face of the new tet (a,b,c,v) that contains edge (from,to) of the boundary triangle.
  constexpr int kEdgeFace[3] = { 2, 0, 1 }; // edges ab, bc, ca
  TetId lastTet = -1;
  std::size_t reused = 0;
  for (std::size_t i = 0; i < faceCount; ++i)
  {
    const InsertionWorkspace::BoundaryFace& bf = ws.boundary[i];
    TetId t;
    if (reused < ws.cavity.size())
    {
      t = ws.cavity[reused++];
      const std::size_t base = 4 * static_cast<std::size_t>(t);
      mesh.tets[base] = bf.v[0];
      mesh.tets[base + 1] = bf.v[1];
      mesh.tets[base + 2] = bf.v[2];
      mesh.tets[base + 3] = v;
      if (Checked)
        mesh.flags[t] = 0;
    }
    else if (Partitioned)
    {
      t = ws.pool->take();
      const std::size_t base = 4 * static_cast<std::size_t>(t);
      mesh.flags[t] = 0;
      mesh.tets[base] = bf.v[0];
      mesh.tets[base + 1] = bf.v[1];
      mesh.tets[base + 2] = bf.v[2];
      mesh.tets[base + 3] = v;
      for (int f = 0; f < 3; ++f) // faces not glued stay on the hull, as addTet leaves them
        mesh.neighbors[base + f] = kNoNeighbor;
    }
    else
      t = mesh.addTet(bf.v[0], bf.v[1], bf.v[2], v);
    const std::size_t base = 4 * static_cast<std::size_t>(t);
    mesh.neighbors[base + 3] = bf.outside;
    if (bf.outside != kNoNeighbor)
      mesh.neighbors[static_cast<std::size_t>(bf.outside)] = makeFaceRef(t, 3);
    if (Checked && bf.constrained)
      mesh.flags[t] = static_cast<std::uint8_t>(kConstrainedFace0 << 3);
    lastTet = t;
    if (directed)
    {
      // Every directed edge occurs exactly once on an unconstrained cavity's boundary, so
      // all are stored first and looked up second: no "first or second visit" branch, which
      // is a coin flip per edge and mispredicted half the time.
      ws.cone[i] = t;
      if (local)
      {
        const std::uint8_t* l = &ws.faceLocal[3 * i];
        for (int e = 0; e < 3; ++e)
          ws.localEdges[l[e] * InsertionWorkspace::kMaxLocal + l[(e + 1) % 3]] =
            makeFaceRef(t, kEdgeFace[e]);
        continue;
      }
      for (int e = 0; e < 3; ++e)
      {
        const VertexId from = bf.v[e], to = bf.v[(e + 1) % 3];
        std::size_t slot = directedEdgeHash(from, to, mask);
        while (ws.edgeTable[slot].stamp == stamp)
          slot = (slot + 1) & mask;
        ws.edgeTable[slot] = { stamp, from, to, makeFaceRef(t, kEdgeFace[e]) };
      }
      continue;
    }
    for (int e = 0; e < 3; ++e)
    {
      const VertexId from = bf.v[e], to = bf.v[(e + 1) % 3];
      const FaceRef mine = makeFaceRef(t, kEdgeFace[e]);
      // The neighbouring cone tet holds the same edge in the opposite direction. Each
      // directed edge occurs once, so a matched slot can simply be left behind.
      std::size_t slot = edgeHash(from, to, mask);
      for (;;)
      {
        InsertionWorkspace::EdgeSlot& s = ws.edgeTable[slot];
        if (s.stamp != stamp)
        {
          s = { stamp, from, to, mine };
          break;
        }
        if (s.from == to && s.to == from)
        {
          mesh.neighbors[base + kEdgeFace[e]] = s.face;
          mesh.neighbors[static_cast<std::size_t>(s.face)] = mine;
          break;
        }
        slot = (slot + 1) & mask;
      }
    }
  }
  if (directed && local)
    for (std::size_t i = 0; i < faceCount; ++i)
    {
      // The neighbouring cone tet holds the same edge in the opposite direction.
      const std::uint8_t* l = &ws.faceLocal[3 * i];
      const std::size_t base = 4 * static_cast<std::size_t>(ws.cone[i]);
      for (int e = 0; e < 3; ++e)
        mesh.neighbors[base + kEdgeFace[e]] =
          ws.localEdges[l[(e + 1) % 3] * InsertionWorkspace::kMaxLocal + l[e]];
    }
  else if (directed)
    for (std::size_t i = 0; i < faceCount; ++i)
    {
      const InsertionWorkspace::BoundaryFace& bf = ws.boundary[i];
      const std::size_t base = 4 * static_cast<std::size_t>(ws.cone[i]);
      for (int e = 0; e < 3; ++e)
      {
        // The neighbouring cone tet holds the same edge in the opposite direction.
        const VertexId from = bf.v[(e + 1) % 3], to = bf.v[e];
        std::size_t slot = directedEdgeHash(from, to, mask);
        for (;;)
        {
          const InsertionWorkspace::EdgeSlot& s = ws.edgeTable[slot];
          if (s.from == from && s.to == to && s.stamp == stamp)
            break;
          slot = (slot + 1) & mask;
        }
        mesh.neighbors[base + kEdgeFace[e]] = ws.edgeTable[slot].face;
      }
    }
  // Cavity slots not reused (only possible in degenerate checked-mode cavities).
  for (std::size_t i = reused; i < ws.cavity.size(); ++i)
  {
    mesh.flags[ws.cavity[i]] = 0;
    if (Partitioned)
    {
      mesh.tets[4 * static_cast<std::size_t>(ws.cavity[i])] = kDeletedTet;
      ws.pool->freed.push_back(ws.cavity[i]);
    }
    else
      mesh.deleteTet(ws.cavity[i]);
  }
  return lastTet;
}

// Partitioned (insertInHalves, MeshHalves): the walk and the cavity stay within the side's
// tets, else the answer is Postponed and the mesh unchanged. The side's tets (all 4 vertices
// its own) are created and deleted only by this side; tets with vertices of both sides are
// neither created nor deleted by anyone during the phase. So the walk may cross any face with
// a vertex of its own (the entries of such faces are written only by this side, if at all),
// and the cavity may hold only the side's tets. Nothing this side reads is written by the
// other, which makes each side's work, and the mesh, independent of the thread schedule.
template<bool Checked, bool Partitioned = false>
InsertResult insertImpl(TetMesh& mesh, VertexId v, TetId hint, InsertionWorkspace& ws)
{
  const double* p = mesh.point(v);
  if (Partitioned && (hint < 0 || hint >= mesh.tetCapacity() || mesh.isDeleted(hint)))
    return { InsertStatus::Postponed, -1, -1 };
  if (hint < 0 || hint >= mesh.tetCapacity() || mesh.isDeleted(hint))
  {
    hint = -1;
    for (TetId t = mesh.tetCapacity() - 1; t >= 0 && hint < 0; --t)
      if (!mesh.isDeleted(t))
        hint = t;
    if (hint < 0)
      return { InsertStatus::OutsideMesh, -1, -1 };
  }
  TetId t = walk<Partitioned>(
    mesh, p, hint, ws.rng, ws.partition, v < ws.smallLatticeVertices ? ws.smallLatticeVertices : 0);
  if (Partitioned && t < 0)
    return { InsertStatus::Postponed, -1, -1 };
  // A walk that reaches the hull proves p outside only for a convex triangulation (the box);
  // once exterior tets are gone the domain may be non-convex, so look everywhere.
  if (t < 0 && Checked)
    t = exhaustiveLocate(mesh, p);
  if (t < 0)
    return { InsertStatus::OutsideMesh, -1, -1 };
  for (int k = 0; k < 4; ++k)
  {
    const VertexId w = mesh.vertex(t, k);
    const double* q = mesh.point(w);
    if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2])
      return { InsertStatus::Duplicate, t, w };
  }
  if constexpr (Partitioned)
    if (!ws.partition->ownsTet(&mesh.tets[4 * static_cast<std::size_t>(t)]))
      return { InsertStatus::Postponed, t, -1 };
  if (Checked)
  {
    const double* coords = mesh.coords.data();
    for (int f = 0; f < 4; ++f)
      if (faceConstrained(mesh, t, f) && faceOrient(mesh, coords, t, f, p) == 0)
        return { InsertStatus::OnConstraint, t, -1 };
  }
  bool starShaped = false;
  if (Checked)
  {
    bool crossed = false;
    starShaped = growCavityChecked<Partitioned>(mesh, v, t, ws, &crossed);
    if (Partitioned && crossed)
      return { InsertStatus::Postponed, t, -1 };
    starShaped = starShaped && noVertexSwallowed(mesh, ws);
  }
  else if (!growCavityFast<Partitioned>(mesh, v, t, ws))
    return { InsertStatus::Postponed, t, -1 };
  if (Checked && !starShaped)
  {
    if (shrinkToStar(mesh, p, t, ws) == ShrinkOutcome::OnConstraint)
    {
      clearMarks(mesh, ws);
      return { InsertStatus::OnConstraint, t, -1 };
    }
    collectBoundary(mesh, ws);
  }
  if (Checked)
    for (TetId r : ws.rejected)
      mesh.flags[r] = static_cast<std::uint8_t>(mesh.flags[r] & ~(kInCavity | kRejected));
  // The cone needs boundary.size() slots; the cavity gives back cavity.size().
  if constexpr (Partitioned)
    if (ws.boundary.size() > ws.cavity.size() &&
      ws.pool->available() < ws.boundary.size() - ws.cavity.size())
    {
      if (Checked)
        for (TetId c : ws.cavity)
          mesh.flags[c] = static_cast<std::uint8_t>(mesh.flags[c] & ~(kInCavity | kRejected));
      else
        unmarkCavity(mesh.tets.data(), ws);
      return { InsertStatus::Postponed, t, -1 };
    }
  const TetId created = fillCavity<Checked, Partitioned>(mesh, v, ws);
  return { InsertStatus::Inserted, created, -1 };
}

// Glues the faces of a handful of tets by brute-force matching of their vertex triples.
void glueByMatching(TetMesh& mesh, const TetId* tets, int count)
{
  for (int i = 0; i < count; ++i)
    for (int f = 0; f < 4; ++f)
    {
      VertexId a[3];
      for (int k = 0; k < 3; ++k)
        a[k] = mesh.vertex(tets[i], kFaceVertices[f][k]);
      std::sort(a, a + 3);
      for (int j = 0; j < count; ++j)
        for (int g = 0; g < 4 && j != i; ++g)
        {
          VertexId b[3];
          for (int k = 0; k < 3; ++k)
            b[k] = mesh.vertex(tets[j], kFaceVertices[g][k]);
          std::sort(b, b + 3);
          if (std::equal(a, a + 3, b))
            mesh.glue(tets[i], f, tets[j], g);
        }
    }
}

// Points per phase below which splitting is not worth starting threads and sizing ranges.
constexpr std::size_t kMinHalvesPoints = 16384;

} // namespace

// Everything one side writes while inserting, on cache lines of its own: the two threads
// would otherwise share lines (slot counters, hints) and stall each other on every insertion.
struct alignas(64) Side
{
  InsertionWorkspace ws;
  SlotPool pool;
  SpacePartition partition;
  TetId hint = -1;
  std::vector<VertexId> points, postponed;
  std::vector<std::pair<VertexId, VertexId>> duplicates;
};

struct Halves
{
  Side side[2];
};

// Gives each side a private range of tet slots (side 0 also the mesh's free slots), about
// `slots` each; a side that runs out postpones its remaining points. Side 1's range ends the
// arrays, so what it leaves unused is cut off by closeSlotRanges.
void openSlotRanges(TetMesh& mesh, Side* side, std::size_t slots0, std::size_t slots1)
{
  const TetId first = mesh.tetCapacity();
  const TetId size0 = static_cast<TetId>(slots0 + 1024);
  const TetId size1 = static_cast<TetId>(slots1 + 1024);
  const std::size_t total = static_cast<std::size_t>(first) + size0 + size1;
  if (4 * total > mesh.tets.capacity())
  {
    mesh.tets.reserve(4 * (total + total / 16));
    mesh.neighbors.reserve(4 * (total + total / 16));
    mesh.flags.reserve(total + total / 16);
  }
  // Not filled (FlatArray): each side writes the slots it takes, so the fresh pages are first
  // touched by the thread that uses them.
  mesh.tets.resize(4 * total);
  mesh.neighbors.resize(4 * total);
  mesh.flags.resize(total);
  side[0].pool.freed = std::move(mesh.freeTets);
  mesh.freeTets.clear();
  side[0].pool.next = first;
  side[0].pool.end = first + size0;
  side[1].pool.freed.clear();
  side[1].pool.next = first + size0;
  side[1].pool.end = static_cast<TetId>(total);
}

// Closes the sides' ranges: side 1's tets move down to follow side 0's last one (no gap of
// unused slots is left in the arrays), side 1's unused end is cut off, and the freed slots go
// to the free list. Every neighbour reference into the moved block is moved with it.
TetRelocation closeSlotRanges(TetMesh& mesh, Side* side, bool twoThreads)
{
  TetRelocation moved;
  moved.from = side[0].pool.end;
  moved.to = side[1].pool.next;
  moved.shift = side[0].pool.end - side[0].pool.next;
  const bool sideOneUsed = moved.to > moved.from;
  // With nothing to move, side 0's unused slots are the arrays' end: cut off too.
  const TetId end = sideOneUsed ? moved.to - moved.shift : side[0].pool.next;
  if (moved.shift > 0 && sideOneUsed)
  {
    // Down, so a forward copy (memmove) is right though the ranges overlap.
    const std::size_t from = static_cast<std::size_t>(moved.from);
    const std::size_t to = static_cast<std::size_t>(moved.to);
    const std::size_t shift = static_cast<std::size_t>(moved.shift);
    std::copy(mesh.tets.begin() + 4 * from,
      mesh.tets.begin() + 4 * to,
      mesh.tets.begin() + 4 * (from - shift));
    std::copy(mesh.neighbors.begin() + 4 * from,
      mesh.neighbors.begin() + 4 * to,
      mesh.neighbors.begin() + 4 * (from - shift));
    std::copy(
      mesh.flags.begin() + from, mesh.flags.begin() + to, mesh.flags.begin() + (from - shift));
    // References between moved tets move by the shift; a tet outside the block gets its
    // reference back to the moved tet rewritten (freed slots' entries are stale: skipped).
    // Each entry is written once, by the tet it belongs to or across its one face: the two
    // halves of the block side by side.
    const TetId first = moved.from - moved.shift;
    constexpr TetId kMinHalves = 65536;
    splitAt(twoThreads && end - first >= kMinHalves,
      (end - first) / 2,
      end - first,
      [&](int, TetId begin, TetId stop)
      {
        for (TetId t = first + begin; t < first + stop; ++t)
        {
          if (mesh.isDeleted(t))
            continue;
          for (int f = 0; f < 4; ++f)
          {
            FaceRef& n = mesh.neighbors[4 * static_cast<std::size_t>(t) + f];
            if (n == kNoNeighbor)
              continue;
            if (faceTet(n) >= moved.from && faceTet(n) < moved.to)
              n -= 4 * moved.shift;
            else
              mesh.neighbors[static_cast<std::size_t>(n)] = makeFaceRef(t, f);
          }
        }
      });
    for (TetId& t : side[1].pool.freed)
      t = moved.map(t);
  }
  else
    moved = TetRelocation{};
  mesh.tets.resize(4 * static_cast<std::size_t>(end));
  mesh.neighbors.resize(4 * static_cast<std::size_t>(end));
  mesh.flags.resize(static_cast<std::size_t>(end));
  mesh.freeTets = std::move(side[0].pool.freed);
  mesh.freeTets.insert(mesh.freeTets.end(), side[1].pool.freed.begin(), side[1].pool.freed.end());
  side[0].pool.freed.clear();
  side[1].pool.freed.clear();
  return moved;
}

namespace
{

// Inserts the pending points (renumbered ids, ascending) in two halves of space, split at
// the median of their longest extent, one half per thread; pending becomes the points either
// half postponed (ascending), to be retried. Duplicates are appended as (id, existing).
void insertInHalves(TetMesh& mesh,
  std::vector<VertexId>& pending,
  TetId& hint,
  InsertionWorkspace& mainWs,
  Halves& halves,
  std::vector<std::pair<VertexId, VertexId>>& duplicates,
  bool twoThreads)
{
  const double* coords = mesh.coords.data();
  int axis = 0;
  double split = 0;
  medianSplit(
    pending.size(),
    [&](std::size_t i) { return coords + 3 * static_cast<std::size_t>(pending[i]); },
    axis,
    split);
  Side* side = halves.side;
  for (int k = 0; k < 2; ++k)
  {
    side[k].points.clear();
    side[k].postponed.clear();
    side[k].duplicates.clear();
  }
  for (VertexId v : pending)
    side[coords[3 * static_cast<std::size_t>(v) + axis] < split ? 0 : 1].points.push_back(v);
  if (side[0].points.empty() || side[1].points.empty())
    return;
  // Each side starts from the tet holding its first point: that tet has a vertex of the side
  // (it holds a point of the side's half), so it is never the other side's alone.
  for (int k = 0; k < 2; ++k)
  {
    side[k].hint = walk(mesh, mesh.point(side[k].points[0]), hint, mainWs.rng);
    if (side[k].hint < 0)
      return;
  }

  // 7 slots per point: an insertion adds 6.7 tets on average in a Delaunay mesh.
  openSlotRanges(mesh, side, 7 * side[0].points.size(), 7 * side[1].points.size());

  auto work = [&mesh, side, coords, axis, split, &mainWs](int k)
  {
    Side& me = side[k];
    me.partition = { coords, axis, split, k == 0 };
    me.ws.partition = &me.partition;
    me.ws.pool = &me.pool;
    me.ws.perturbationIds = mainWs.perturbationIds;
    me.ws.smallLatticeVertices = mainWs.smallLatticeVertices;
    for (VertexId v : me.points)
    {
      const InsertResult r = insertImpl<false, true>(mesh, v, me.hint, me.ws);
      if (r.status == InsertStatus::Postponed)
        me.postponed.push_back(v);
      else
      {
        me.hint = r.tet;
        if (r.status == InsertStatus::Duplicate)
          me.duplicates.emplace_back(v, r.existing);
      }
    }
  };
  runPair(twoThreads, work);

  const TetRelocation moved = closeSlotRanges(mesh, side, twoThreads);
  hint = moved.map(side[1].hint);
  for (int k = 0; k < 2; ++k)
    duplicates.insert(duplicates.end(), side[k].duplicates.begin(), side[k].duplicates.end());
  pending.clear();
  std::merge(side[0].postponed.begin(),
    side[0].postponed.end(),
    side[1].postponed.begin(),
    side[1].postponed.end(),
    std::back_inserter(pending));
}

} // namespace

struct MeshHalves::State
{
  TetMesh* mesh = nullptr;
  Halves halves;
  bool open = false;
};

MeshHalves::MeshHalves(TetMesh& mesh,
  int axis,
  double split,
  std::size_t points0,
  std::size_t points1,
  std::size_t slotsPerPoint)
  : state_(std::make_unique<State>())
{
  state_->mesh = &mesh;
  Side* side = state_->halves.side;
  for (int k = 0; k < 2; ++k)
  {
    side[k].partition = { mesh.coords.data(), axis, split, k == 0 };
    side[k].ws.partition = &side[k].partition;
    side[k].ws.pool = &side[k].pool;
  }
  openSlotRanges(mesh, side, slotsPerPoint * points0, slotsPerPoint * points1);
  state_->open = true;
}

MeshHalves::~MeshHalves()
{
  finish();
}

bool MeshHalves::owns(int side, VertexId v) const
{
  return state_->halves.side[side].partition.owns(v);
}

TetId MeshHalves::locate(int side, const double* p, TetId hint)
{
  const TetMesh& mesh = *state_->mesh;
  if (hint < 0 || hint >= mesh.tetCapacity() || mesh.isDeleted(hint))
    return kPostponed;
  Side& me = state_->halves.side[side];
  return walk<true>(mesh, p, hint, me.ws.rng, &me.partition);
}

InsertResult MeshHalves::insert(int side, VertexId v, TetId hint)
{
  return insertImpl<true, true>(*state_->mesh, v, hint, state_->halves.side[side].ws);
}

TetRelocation MeshHalves::finish()
{
  if (!state_->open)
    return {};
  state_->open = false;
  return closeSlotRanges(*state_->mesh, state_->halves.side, wantTwoThreads(0));
}

InsertResult insertVertex(TetMesh& mesh, VertexId v, TetId hint, InsertionWorkspace& workspace)
{
  return insertImpl<true>(mesh, v, hint, workspace);
}

TetId locatePoint(const TetMesh& mesh, const double* p, TetId hint)
{
  if (hint < 0 || hint >= mesh.tetCapacity() || mesh.isDeleted(hint))
    return exhaustiveLocate(mesh, p);
  std::uint64_t rng = kWalkSeed;
  const TetId t = walk(mesh, p, hint, rng);
  return t >= 0 ? t : exhaustiveLocate(mesh, p); // non-convex meshes: see insertImpl
}

TetId walkToPoint(const TetMesh& mesh, const double* p, TetId hint)
{
  if (hint < 0 || hint >= mesh.tetCapacity() || mesh.isDeleted(hint))
    return -1;
  std::uint64_t rng = kWalkSeed;
  return walk(mesh, p, hint, rng);
}

DelaunayResult buildDelaunay(TetMesh& mesh, const DelaunayOptions& options)
{
  // The caller's array is the input, kept aside until the end (the result gets a new one).
  const std::vector<double> input = std::move(mesh.coords);
  mesh.coords = std::vector<double>();
  return buildDelaunay(mesh, input.data(), static_cast<VertexId>(input.size() / 3), options);
}

DelaunayResult buildDelaunay(TetMesh& mesh,
  const double* points,
  VertexId n,
  const DelaunayOptions& options)
{
  DelaunayResult result;
  mesh.coords.clear();
  mesh.tets.clear();
  mesh.neighbors.clear();
  mesh.flags.clear();
  mesh.freeTets.clear();

  // Outside the exact range the predicates overflow or underflow and the mesh would be
  // garbage (a fuzzer found a point at 7.8e143 giving inverted tets and broken adjacency).
  result.error = predicates::coordinateRangeError(points, n, "vertex");
  if (!result.error.empty())
  {
    mesh.coords.assign(points, points + 3 * static_cast<std::size_t>(n));
    return result;
  }

  // Bounding box, enlarged by boxEnlargement diagonals on every side.
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  for (VertexId v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k)
    {
      const double c = points[3 * static_cast<std::size_t>(v) + k];
      lo[k] = v == 0 ? c : std::min(lo[k], c);
      hi[k] = v == 0 ? c : std::max(hi[k], c);
    }
  double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
    (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  if (diagonal == 0)
    diagonal = std::max({ 1.0, std::abs(lo[0]), std::abs(lo[1]), std::abs(lo[2]) });
  const double margin = std::max(options.boxEnlargement, 0.01) * diagonal;

  // Reserve for the expected ~6.8 tets per point (uniform random points) so the arrays never
  // reallocate (and never transiently double the memory) during insertion, with room for the
  // slots the halves leave unused (insertInHalves). Reserved pages cost nothing until touched.
  const std::size_t expectedTets = static_cast<std::size_t>(n) * 15 / 2 + 64;
  mesh.tets.reserve(4 * expectedTets);
  mesh.neighbors.reserve(4 * expectedTets);
  mesh.flags.reserve(expectedTets);
  adviseHugePages(mesh.tets);
  adviseHugePages(mesh.neighbors);
  adviseHugePages(mesh.flags);

  // Insertion order, and renumbering: the points are copied in insertion order so that the
  // coordinates of neighbouring tets are neighbours in memory (input order is often random,
  // and then every in-sphere test would miss the cache). The symbolic perturbation still
  // uses the caller's ids, so the mesh is the same as without renumbering; the tets are
  // mapped back to the caller's ids at the end.
  // Loops over all points or tets run in halves on two threads (the results are the same).
  const bool twoThreads = options.partitioned && wantTwoThreads(options.threads);
  constexpr std::size_t kMinHalves = 65536;
  std::vector<std::size_t> roundStarts;
  std::vector<VertexId> originalId = brioOrder(points, n, 0x5eed5eedULL, &roundStarts, twoThreads);
  for (VertexId v = n; v < n + 8; ++v)
    originalId.push_back(v);
  // The renumbered copy has room for the 8 box corners (ids n..n+7 in both numberings), on
  // huge pages; at the end the input order is copied back into it. The input is read in
  // place: no copy of every point into fresh memory first (0.05 s for 1M points).
  mesh.coords.reserve(3 * (static_cast<std::size_t>(n) + 8));
  adviseHugePages(mesh.coords);
  mesh.coords.resize(3 * static_cast<std::size_t>(n));
  forHalves(static_cast<std::size_t>(n),
    twoThreads,
    kMinHalves,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t i = begin; i < end; ++i)
        for (int k = 0; k < 3; ++k)
          mesh.coords[3 * i + k] = points[3 * static_cast<std::size_t>(originalId[i]) + k];
    });
  auto restoreInputOrder = [&]()
  {
    forHalves(3 * static_cast<std::size_t>(n),
      twoThreads,
      kMinHalves,
      [&](std::size_t begin, std::size_t end)
      { std::copy(points + begin, points + end, mesh.coords.begin() + begin); });
  };

  result.firstBoxVertex = n;
  for (int corner = 0; corner < 8; ++corner)
    mesh.addVertex((corner & 1) ? hi[0] + margin : lo[0] - margin,
      (corner & 2) ? hi[1] + margin : lo[1] - margin,
      (corner & 4) ? hi[2] + margin : lo[2] - margin);

  // The 8 corners are cospherical, so which triangulation of the box is Delaunay is decided
  // by the symbolic perturbation: take the 4-subsets whose (perturbed) circumsphere is empty
  // of the other corners. That is 5 tets or 6 depending on the perturbation, and it keeps the
  // whole construction consistently (perturbed-)Delaunay from the start.
  TetId box[8];
  int boxCount = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = i + 1; j < 8; ++j)
      for (int k = j + 1; k < 8; ++k)
        for (int l = k + 1; l < 8; ++l)
        {
          VertexId v[4] = { n + i, n + j, n + k, n + l };
          const int o = predicates::orient3d(
            mesh.point(v[0]), mesh.point(v[1]), mesh.point(v[2]), mesh.point(v[3]));
          if (o == 0)
            continue;
          if (o < 0)
            std::swap(v[0], v[1]);
          bool empty = true;
          for (int m = 0; m < 8 && empty; ++m)
          {
            const VertexId w = n + m;
            if (w != v[0] && w != v[1] && w != v[2] && w != v[3])
              empty = predicates::insphereSoS(mesh, v[0], v[1], v[2], v[3], w) < 0;
          }
          if (empty && boxCount < 8)
            box[boxCount++] = mesh.addTet(v[0], v[1], v[2], v[3]);
        }
  glueByMatching(mesh, box, boxCount);

  InsertionWorkspace ws;
  ws.perturbationIds = originalId.data();
  std::vector<VertexId> rankedId;
  if (options.perturbationRank)
  {
    rankedId.resize(originalId.size());
    for (std::size_t i = 0; i < originalId.size(); ++i)
      rankedId[i] = originalId[i] < n ? options.perturbationRank[originalId[i]] : originalId[i];
    ws.perturbationIds = rankedId.data();
  }
  if (options.smallLatticePredicates && smallLatticeBits(points, n, lo) > 0)
    ws.smallLatticeVertices = n;
  TetId hint = box[0];
  std::vector<std::pair<VertexId, VertexId>> duplicates; // (id, the id it duplicates)
  auto insertInOrder = [&](VertexId v)
  {
    const InsertResult r = insertImpl<false>(mesh, v, hint, ws);
    if (r.status == InsertStatus::Inserted)
      hint = r.tet;
    else if (r.status == InsertStatus::Duplicate)
    {
      duplicates.emplace_back(v, r.existing);
      hint = r.tet;
    }
    else
      return false;
    return true;
  };
  // Large rounds go in two halves of space side by side (insertInHalves), twice (the second
  // time across the first split, for the points near it), and what is left in order.
  std::unique_ptr<Halves> halves;
  std::vector<VertexId> pending;
  auto skipped = [&](std::size_t i) { return options.skip && options.skip[originalId[i]]; };
  for (std::size_t r = 0; r < roundStarts.size(); ++r)
  {
    const std::size_t begin = roundStarts[r];
    const std::size_t end = r + 1 < roundStarts.size() ? roundStarts[r + 1] : n;
    pending.clear();
    if (options.partitioned && end - begin >= kMinHalvesPoints)
    {
      if (!halves)
        halves = std::make_unique<Halves>();
      for (std::size_t i = begin; i < end; ++i)
        if (!skipped(i))
          pending.push_back(static_cast<VertexId>(i));
      for (int phase = 0; phase < 2 && pending.size() >= kMinHalvesPoints; ++phase)
        insertInHalves(mesh, pending, hint, ws, *halves, duplicates, twoThreads);
    }
    else
      for (std::size_t i = begin; i < end; ++i)
        if (!skipped(i))
          pending.push_back(static_cast<VertexId>(i));
    for (VertexId v : pending)
      if (!insertInOrder(v))
      {
        result.error = "vertex " + std::to_string(originalId[static_cast<std::size_t>(v)]) +
          " could not be inserted";
        restoreInputOrder();
        return result;
      }
  }
  std::sort(duplicates.begin(), duplicates.end());
  for (const auto& [v, existing] : duplicates)
  {
    result.duplicates.push_back(originalId[static_cast<std::size_t>(v)]);
    result.duplicateOf.push_back(originalId[static_cast<std::size_t>(existing)]);
  }
  restoreInputOrder();
  forHalves(static_cast<std::size_t>(mesh.tetCapacity()),
    twoThreads,
    kMinHalves,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
        if (!mesh.isDeleted(static_cast<TetId>(t)))
          for (int k = 0; k < 4; ++k)
          {
            VertexId& id = mesh.tets[4 * t + k];
            id = originalId[static_cast<std::size_t>(id)];
          }
    });

  if (options.validate)
  {
    std::vector<VertexId> absent = result.duplicates;
    for (VertexId v = 0; options.skip && v < n; ++v)
      if (options.skip[v])
        absent.push_back(v);
    const std::string msg = validateDelaunayMesh(mesh, n + 8, absent);
    if (!msg.empty())
    {
      result.error = "Delaunay validation failed: " + msg;
      return result;
    }
  }
  result.ok = true;
  return result;
}

} // namespace tetmesher
