#include "ConstraintRecovery.h"

#include "CavityCone.h"
#include "DeepEdgeRemoval.h"
#include "Delaunay.h"
#include "DirectionalEdgeRecovery.h"
#include "EpochHashTable.h"
#include "Flips.h"
#include "MeshTopology.h"
#include "Predicates.h"
#include "RecoveryGeometry.h"
#include "TriangleBoxGrid.h"
#include "TriangleDistance.h"
#include "TriangleIndex.h"
#include "TriangleIntersection.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <unordered_map>

namespace tetmesher
{
namespace
{

struct TupleHash
{
  template<std::size_t N>
  std::size_t operator()(const std::array<VertexId, N>& k) const
  {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (VertexId v : k)
      h = (h ^ static_cast<std::uint32_t>(v)) * 0x100000001b3ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// A sorted tuple of up to four vertex ids packed in two words (the key of the memo).
struct PackedKey
{
  std::uint64_t hi, lo;
  bool operator==(const PackedKey& o) const { return hi == o.hi && lo == o.lo; }
};
inline std::uint64_t pack(VertexId a, VertexId b)
{
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
    static_cast<std::uint32_t>(b);
}
inline void sort2(VertexId& a, VertexId& b)
{
  if (b < a)
    std::swap(a, b);
}
inline PackedKey edgeMemoKey(VertexId a, VertexId b)
{
  sort2(a, b);
  return { pack(a, b), 0 };
}
inline PackedKey faceMemoKey(VertexId a, VertexId b, VertexId c)
{
  sort2(a, b);
  sort2(b, c);
  sort2(a, b);
  return { pack(a, b), static_cast<std::uint32_t>(c) };
}
inline PackedKey tetMemoKey(const TetVertices& t)
{
  VertexId a = t[0], b = t[1], c = t[2], d = t[3];
  sort2(a, b);
  sort2(c, d);
  sort2(a, c);
  sort2(b, d);
  sort2(b, c);
  return { pack(a, b), pack(c, d) };
}

struct PackedKeyHash
{
  std::size_t operator()(const PackedKey& k) const
  {
    const std::uint64_t h = k.hi * 0x9e3779b97f4a7c15ull ^ k.lo * 0xc2b2ae3d27d4eb4full;
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

// The memo of one flip search: a sorted vertex tuple to its (non-negative) count.
using FlatMemo = EpochHashTable<PackedKey, int, PackedKeyHash>;

// The value of `key` in `memo`, computed by `compute` the first time.
template<typename Compute>
int memoize(FlatMemo& memo, const PackedKey& key, Compute&& compute)
{
  if (const int* cached = memo.find(key))
    return *cached;
  const int value = compute();
  memo.insert(key, value);
  return value;
}

// The memos of one measure (tets, faces, edges).
struct MemoCaches
{
  FlatMemo tets, faces, edges;
};

// The measure of how much of the mesh a missing item cuts, with the bounding box of the
// item (of all its parts for a compound measure): an entity whose box is separated from it
// scores 0 without an exact test.
struct ItemCost : FlipCost
{
  std::array<double, 6> box = { 0, 0, 0, 0, 0, 0 }; // min x, y, z, max x, y, z
  // The ends of the segment when the item is an input edge alone (else -1): a search seeded
  // at one end can rule out tets of that end's star by a cone test (collectPipe).
  VertexId segment[2] = { -1, -1 };
};

// True when the open set that the points of `ids` span misses `box`, as they all lie on or
// beyond one side of it: a tet's interior (tetInterior) then does (a flat tet, all on the
// side, has none), and so does an open triangle or segment with one point strictly beyond,
// since each of its points weighs every vertex.
template<std::size_t N>
bool separatedFromBox(const TetMesh& mesh,
  const std::array<double, 6>& box,
  const std::array<VertexId, N>& ids,
  bool tetInterior)
{
  for (int k = 0; k < 3; ++k)
  {
    double lo = mesh.point(ids[0])[k], hi = lo;
    for (std::size_t i = 1; i < N; ++i)
    {
      lo = std::min(lo, mesh.point(ids[i])[k]);
      hi = std::max(hi, mesh.point(ids[i])[k]);
    }
    if (tetInterior ? (hi <= box[k] || lo >= box[k + 3])
                    : ((hi <= box[k] && lo < box[k]) || (lo >= box[k + 3] && hi > box[k + 3])))
      return true;
  }
  return false;
}

// Set of vertex tuples for the scratch of one flip search step.
template<typename Key>
using ScratchSet = EpochHashTable<Key, std::uint8_t, TupleHash>;

// The same measure, each exact test run once per (unordered) tet, face or edge: a flip search
// prices the same entities again and again (every move rescans its pipe, every edge removal
// prices all ring triangulations). All three tests are symmetric in their vertices. Entities
// separated from the item's box score 0 before the look-up (the tests count tet interiors,
// open triangles and open segments, which miss the item when they miss its box; a face or
// edge with a vertex on the plane of a flat item, common on CAD parts, is separated when its
// other vertices lie beyond that plane).
// `caches` must be empty; the measure keeps it alive.
FlipCost memoized(const ItemCost& base, const TetMesh& mesh, std::shared_ptr<MemoCaches> caches)
{
  const TetMesh* m = &mesh;
  const std::array<double, 6> box = base.box;
  FlatMemo* tets = &caches->tets;
  FlatMemo* faces = &caches->faces;
  FlatMemo* edges = &caches->edges;
  FlipCost c;
  if (base.tet)
    c.tet = [caches, tets, f = base.tet, m, box](const TetVertices& t)
    {
      if (separatedFromBox(*m, box, t, true))
        return 0;
      return memoize(*tets, tetMemoKey(t), [&] { return f(t); });
    };
  if (base.face)
    c.face = [caches, faces, f = base.face, m, box](VertexId x, VertexId y, VertexId z)
    {
      if (separatedFromBox(*m, box, std::array<VertexId, 3>{ x, y, z }, false))
        return 0;
      return memoize(*faces, faceMemoKey(x, y, z), [&] { return f(x, y, z); });
    };
  if (base.edge)
    c.edge = [caches, edges, f = base.edge, m, box](VertexId u, VertexId v)
    {
      if (separatedFromBox(*m, box, std::array<VertexId, 2>{ u, v }, false))
        return 0;
      return memoize(*edges, edgeMemoKey(u, v), [&] { return f(u, v); });
    };
  return c;
}

// Cost-neutral moves tried by the one-move lookahead of a stuck flip search.
constexpr std::size_t kMaxNeutral = 48;

class Recovery
{
public:
  Recovery(TetMesh& mesh, const SurfaceInput& surface, const RecoveryOptions& options)
    : mesh_(mesh)
    , surface_(surface)
    , options_(options)
    , start_(std::chrono::steady_clock::now())
    , lastPoll_(start_)
  {
    index_.rebuild(mesh_);
    deep_.memoizeCandidates = true;
    // The edges are sorted (a < b): those of input point a start at edgeStart_[a].
    edgeStart_.assign(static_cast<std::size_t>(surface_.pointCount) + 1, 0);
    for (const auto& edge : surface_.edges)
      ++edgeStart_[edge[0] + 1];
    for (std::size_t v = 0; v + 1 < edgeStart_.size(); ++v)
      edgeStart_[v + 1] += edgeStart_[v];
    // The triangles of each input point, in increasing order.
    vertexTriangleStart_.assign(static_cast<std::size_t>(surface_.pointCount) + 1, 0);
    for (const auto& t : surface_.triangles)
      for (VertexId v : t)
        ++vertexTriangleStart_[v + 1];
    for (std::size_t v = 0; v + 1 < vertexTriangleStart_.size(); ++v)
      vertexTriangleStart_[v + 1] += vertexTriangleStart_[v];
    vertexTriangles_.resize(3 * surface_.triangles.size());
    {
      std::vector<std::int32_t> next(vertexTriangleStart_.begin(), vertexTriangleStart_.end() - 1);
      for (std::size_t i = 0; i < surface_.triangles.size(); ++i)
        for (VertexId v : surface_.triangles[i])
          vertexTriangles_[next[v]++] = static_cast<std::int32_t>(i);
    }
    triangleBoxes_.reserve(surface_.triangles.size());
    for (const auto& t : surface_.triangles)
    {
      std::array<double, 6> box;
      for (int k = 0; k < 3; ++k)
      {
        box[k] = std::min({ point(t[0])[k], point(t[1])[k], point(t[2])[k] });
        box[k + 3] = std::max({ point(t[0])[k], point(t[1])[k], point(t[2])[k] });
      }
      triangleBoxes_.push_back(box);
    }
  }

  RecoveryResult run(const std::function<bool(double)>& progress);

private:
  const double* point(VertexId v) const { return mesh_.point(v); }
  // The index of input edge (a,b) in surface_.edges, or -1.
  std::int32_t inputEdgeIndex(VertexId a, VertexId b) const
  {
    if (a > b)
      std::swap(a, b);
    if (a < 0 || b >= surface_.pointCount)
      return -1; // Steiner points and the Delaunay box are on no input edge
    for (std::int32_t e = edgeStart_[a]; e < edgeStart_[a + 1]; ++e)
    {
      if (surface_.edges[e][1] == b)
        return e;
    }
    return -1;
  }
  bool isInputEdge(VertexId a, VertexId b) const { return inputEdgeIndex(a, b) >= 0; }
  // True when face ref `face` is a live tet's face with the vertices of `tri`.
  bool faceHolds(FaceRef face, const std::array<VertexId, 3>& tri) const
  {
    const TetId t = faceTet(face);
    if (t >= mesh_.tetCapacity() || mesh_.isDeleted(t))
      return false;
    const VertexId apex = mesh_.vertex(t, faceIndex(face));
    for (VertexId v : tri)
      if (v == apex || localIndex(mesh_, t, v) < 0)
        return false;
    return true;
  }
  TetVertices tetVertices(TetId t) const
  {
    return { mesh_.vertex(t, 0), mesh_.vertex(t, 1), mesh_.vertex(t, 2), mesh_.vertex(t, 3) };
  }
  bool tetMeets(const double* const* simplex, int count, const TetVertices& t) const
  {
    const double* p[4] = { point(t[0]), point(t[1]), point(t[2]), point(t[3]) };
    return geometry::simplexMeetsTetInterior(simplex, count, p);
  }

  ItemCost edgeCost(VertexId a, VertexId b) const;
  ItemCost faceCost(const std::array<VertexId, 3>& tri) const;
  ItemCost edgeAndFacesCost(std::size_t e) const;
  std::array<double, 6> boxOf(std::initializer_list<VertexId> vertices) const;
  // Tets whose tet/face/edge terms of `cost` are positive, grown from the star of `seed`.
  // `tip`: when cost is that of input edge (seed, tip) alone, the other end (else -1), for
  // the cone test outside a flip search (refillEdgeCavity).
  void collectPipe(VertexId seed,
    const FlipCost& cost,
    std::vector<TetId>& pipe,
    VertexId tip = -1);
  // Sum of the measure over t and its faces and edges; cached per tet (checked against its
  // vertices) while the cost is the current flip search's.
  int tetCost(const FlipCost& cost, TetId t);
  int exactTetCost(const FlipCost& cost, const TetVertices& v) const;
  // Greedy strictly-improving flips on the pipe; true when `done()` holds at the end.
  // `search` names the item and its measure (see deepFailuresBySearch_).
  bool flipUntil(VertexId seed,
    const ItemCost& cost,
    const std::function<bool()>& done,
    std::size_t search)
  {
    return flipUntil(seed, cost, memoized(cost, mesh_, emptyMemo()), done, search);
  }
  // The same with the measure memoized already (`cost`, from `exactCost`).
  bool flipUntil(VertexId seed,
    const ItemCost& exactCost,
    const FlipCost& cost,
    const std::function<bool()>& done,
    std::size_t search);
  // Collects the pipe and the flips on it; returns the best strict gain (0: none), with the
  // best move in `best` and the cost-neutral ones appended to `neutral` when given.
  int findMoves(VertexId seed,
    const FlipCost& cost,
    std::vector<TetId>& pipe,
    FlipCandidate& best,
    bool& bestIsFlip23,
    std::vector<FlipCandidate>* neutral);
  bool lookahead(VertexId seed, const FlipCost& cost, std::vector<FlipCandidate>& neutral);
  bool shrinkCrossingShell(const std::vector<TetId>& pipe, const FlipCost& cost);
  // A deep removal of an edge cutting the item that lowers the measure or recovers the item;
  // false, with the same tets (under other ids) when none does. `moved`: tets were replaced.
  bool removeCrossingDeep(const std::vector<TetId>& pipe,
    const FlipCost& cost,
    const std::function<bool()>& done,
    bool& moved);
  bool insertSteinerNear(VertexId seed, const ItemCost& cost);
  // Refills the tets that input edge e cuts (grown until star-shaped, up to maxTets) by the
  // cone from one of its ends (CavityCone.h); true when the edge is then in the mesh. `cost`:
  // the edge's measure, memoized (edgeCost).
  bool refillEdgeCavity(std::size_t e, const FlipCost& cost, int maxTets);
  // Empty memos for a new measure: a cleared one of the pool that no measure holds any more
  // (their slots are reused from search to search), else a new one.
  std::shared_ptr<MemoCaches> emptyMemo()
  {
    for (const auto& caches : memoPool_)
    {
      if (caches.use_count() == 1)
      {
        caches->tets.clear();
        caches->faces.clear();
        caches->edges.clear();
        return caches;
      }
    }
    memoPool_.push_back(std::make_shared<MemoCaches>());
    return memoPool_.back();
  }
  // "input triangles i and j intersect" for the first input triangle of the recovery item
  // `key` (an edge index, or edges.size() + a triangle index) that meets another one other
  // than in a vertex or edge they share; "" if none does.
  std::string intersectingTriangles(std::size_t key) const;
  // "input triangles i and j come within d of each other (...)" for the first triangle of
  // the item `key` that another input triangle (sharing no edge part with it) comes closer
  // to than options_.nearTouchRatio times their longest edge; "" if none does.
  std::string nearlyTouchingTriangles(std::size_t key) const;
  // The input triangles of the recovery item `key` (an edge's triangles, or the triangle).
  std::vector<std::size_t> itemTriangles(std::size_t key) const;
  // On an input triangle (exact), or nearer one than tolerance (floating point): a Steiner
  // point that close is strictly inside by the exact tests but on the surface for any user.
  bool onInputSurface(const double* x, double tolerance) const;
  void markConstrained(FaceRef face);
  // One pass over the tets: a face ref of each input triangle the mesh has (-1 if none), and
  // the input edges of those (edgeInMesh; others may be there too). The Delaunay mesh of the
  // surface points already has most of them, and a star search per item cost more than the
  // flips on big surfaces (bunny00, 75k triangles: a fifth of the recovery).
  void findPresentItems(std::vector<char>& edgeInMesh, std::vector<FaceRef>& triangleFace);
  // True when the time budget is spent or the progress callback asked to abort (polled a
  // few times a second); result_.error then names the item being recovered.
  bool interrupted();
  // replaceTets, stamping the vertices of the new tets as changed.
  void replace(const std::vector<TetId>& oldTets,
    const std::vector<TetVertices>& newTets,
    std::vector<TetId>* created = nullptr);
  void touch(VertexId v)
  {
    if (static_cast<std::size_t>(v) >= vertexStamp_.size())
      vertexStamp_.resize(2 * static_cast<std::size_t>(v) + 16, 0);
    vertexStamp_[v] = ++clock_;
  }
  // A failed flip search remembers the vertices of its pipe and the clock: while no tet
  // incident to one of them has changed, the search would see the same tets and fail again.
  struct Failure
  {
    std::uint64_t clock = 0;
    std::vector<VertexId> vertices;
  };
  // Records the failure of the flip search just ended, with the measure it used (memoized, so
  // its pipe is found again without new exact tests).
  void recordFailure(Failure& failure, VertexId seed, const FlipCost& searchCost);
  bool unchangedSince(const Failure& failure) const;
  // flip23Candidate / edgeRemovalCandidate for the cost of the current flip search, reused
  // while the tets they examine are the same (ids and vertices; flags do not change during a
  // search), so the answer is the same. Cleared per flip search.
  struct CachedCandidate
  {
    std::uint64_t clock = 0;  // 0: not computed
    VertexId p = -1, q = -1;  // edge removal: the edge (its slot is a tet and a vertex pair)
    bool zeroOldCost = false; // the item meets no part of the move's region: no gain
    bool built = false;       // ok and candidate computed
    bool ok = false;
    FlipCandidate candidate;
    std::vector<TetId> shell; // edge removal: the shell and ring it was computed for
    std::vector<VertexId> ring;
  };
  // With gainOnly, a move whose region the item does not meet (old cost 0, so no gain) is
  // answered false without building it: the flip search then only looks for strict gains.
  bool cachedFlip23(TetId t,
    int f,
    const FlipCost& cost,
    FlipCandidate& out,
    bool gainOnly = false);
  bool cachedEdgeRemoval(TetId t,
    VertexId p,
    VertexId q,
    const FlipCost& cost,
    FlipCandidate& out,
    bool gainOnly = false);
  // Inserts the point (true) and repairs the vertex->tet index.
  bool insertSteiner(const double* c, TetId tet);

  TetMesh& mesh_;
  const SurfaceInput& surface_;
  RecoveryOptions options_;
  VertexTetIndex index_;
  std::vector<std::int32_t> edgeStart_; // input edges by their first point (isInputEdge)
  std::vector<std::array<double, 6>> triangleBoxes_;
  // triangleBoxes_ in a grid, built on the first question (most runs never ask).
  mutable std::unique_ptr<TriangleBoxGrid> boxGrid_;
  mutable std::vector<std::int32_t> nearScratch_;
  mutable double largestTriangle_ = -1; // the longest input edge, once nearlyTouchingTriangles asks
  // The triangles whose boxes may come within `margin` of `box` (TriangleBoxGrid::near).
  const std::vector<std::int32_t>& trianglesNear(const std::array<double, 6>& box,
    double margin) const
  {
    if (!boxGrid_)
      boxGrid_ = std::make_unique<TriangleBoxGrid>(triangleBoxes_);
    boxGrid_->near(box, margin, nearScratch_);
    return nearScratch_;
  }
  std::unique_ptr<InsertionWorkspace, InsertionWorkspaceDeleter> workspace_{
    createInsertionWorkspace()
  };
  RecoveryResult result_;
  // Input triangles by point: those of point v are vertexTriangles_[vertexTriangleStart_[v] ..
  // vertexTriangleStart_[v + 1]), in increasing order.
  std::vector<std::int32_t> vertexTriangleStart_, vertexTriangles_;
  // The input triangles of input edge e, in increasing order.
  std::vector<std::array<VertexId, 3>> edgeTriangles(std::size_t e) const
  {
    const VertexId a = surface_.edges[e][0], b = surface_.edges[e][1];
    std::vector<std::array<VertexId, 3>> found;
    for (std::int32_t k = vertexTriangleStart_[a]; k < vertexTriangleStart_[a + 1]; ++k)
    {
      const auto& t = surface_.triangles[vertexTriangles_[k]];
      if (t[0] == b || t[1] == b || t[2] == b)
        found.push_back(t);
    }
    return found;
  }
  std::map<std::size_t, int> steinerPerItem_; // edges by index, then triangles after them
  std::chrono::steady_clock::time_point start_, lastPoll_;
  const std::function<bool(double)>* progress_ = nullptr;
  double progressFraction_ = 0;
  std::string currentItem_; // for the budget / abort message
  bool interrupted_ = false;
  std::vector<std::uint64_t> vertexStamp_;
  std::uint64_t clock_ = 0;
  std::vector<Failure> failures_; // edges by index, then triangles after them
  // Candidates by slot (a face 4t+f, or a tet edge 6t+k), in a pool whose entries keep their
  // vectors from one flip search to the next (no allocation per candidate).
  class CandidateCache
  {
  public:
    CachedCandidate& at(std::size_t slot)
    {
      if (slot >= slots_.size())
        slots_.resize(2 * slot + 16, 0);
      std::uint32_t& index = slots_[slot];
      if (index == 0)
      {
        if (used_ == pool_.size())
          pool_.emplace_back(); // a deque: references to earlier entries stay valid
        pool_[used_].clock = 0;
        index = static_cast<std::uint32_t>(++used_);
        touched_.push_back(slot);
      }
      return pool_[index - 1];
    }
    void clear()
    {
      for (std::size_t slot : touched_)
        slots_[slot] = 0;
      touched_.clear();
      used_ = 0;
    }

  private:
    std::vector<std::uint32_t> slots_; // pool index + 1, or 0
    std::deque<CachedCandidate> pool_;
    std::size_t used_ = 0;
    std::vector<std::size_t> touched_;
  };
  CandidateCache flip23Cache_, edgeRemovalCache_;
  std::vector<TetId> shellScratch_, starScratch_;
  ScratchSet<std::array<VertexId, 3>> triedFaces_; // findMoves scratch
  ScratchSet<std::array<VertexId, 2>> triedEdges_;
  ScratchSet<std::array<VertexId, 2>> edgeScratch_; // shrinkCrossingShell, removeCrossingDeep
  std::vector<TetId> shellScratch2_;
  std::vector<VertexId> ringScratch2_;
  std::vector<std::uint32_t> pipeStamp_;
  std::uint32_t pipeEpoch_ = 0;
  struct TetCostEntry
  {
    TetVertices vertices;
    int cost = 0;
    std::uint64_t epoch = 0; // valid when equal to tetCostEpoch_
  };
  std::uint64_t tetCostEpoch_ = 0;
  std::vector<TetCostEntry> tetCostCache_;
  const FlipCost* tetCostOwner_ = nullptr;
  // collectPipe's cone test of a tet of the seed's star, per tet id while its vertices are the
  // same: the star is walked again for every move of the flip search, and most of it stays.
  struct ConeEntry
  {
    TetVertices vertices;
    std::uint64_t epoch = 0; // valid when equal to tetCostEpoch_
    bool misses = false;
  };
  std::vector<ConeEntry> coneCache_;
  std::vector<VertexId> ringScratch_;
  std::vector<std::shared_ptr<MemoCaches>> memoPool_;
  FlipCost lastSearchCost_; // the memoized measure of the latest flipUntil
  // Deep removals that failed, by search (an input edge alone: 2e; with its triangles:
  // 2e+1; a triangle: 2 edges + t) and by edge, with the vertices whose shells they examined
  // (a Failure record): tried again only once one of those changed, in this flip search or a
  // later one of the same item and measure (the attempt depends on nothing else).
  std::unordered_map<std::size_t, std::unordered_map<std::uint64_t, Failure>> deepFailuresBySearch_;
  std::size_t search_ = 0; // of the current flip search
  // The current flip search's seed and the other end of its segment, when it searches for an
  // input edge alone seeded at one end (ItemCost::segment); coneApex_ is -1 otherwise.
  VertexId coneApex_ = -1, coneTip_ = -1;
  // Input edges are never removed (their faces may not be recovered yet).
  DeepEdgeRemoval deep_{ mesh_, index_, [this](VertexId a, VertexId b) {
                          return isInputEdge(a, b);
                        } };
};

bool Recovery::cachedFlip23(TetId t, int f, const FlipCost& cost, FlipCandidate& out, bool gainOnly)
{
  // The candidate depends on t's vertices, the neighbour across f and its apex.
  CachedCandidate& entry = flip23Cache_.at(static_cast<std::size_t>(makeFaceRef(t, f)));
  FaceRef n = mesh_.neighbor(t, f);
  ringScratch_.assign(
    &mesh_.tets[4 * static_cast<std::size_t>(t)], &mesh_.tets[4 * static_cast<std::size_t>(t)] + 4);
  ringScratch_.push_back(n == kNoNeighbor ? -1 : mesh_.vertex(faceTet(n), faceIndex(n)));
  if (entry.clock == 0 || entry.shell.size() != 1 || entry.shell[0] != n ||
    entry.ring != ringScratch_)
  {
    entry.clock = 1;
    entry.shell.assign(1, n);
    entry.ring = ringScratch_;
    entry.built = false;
    // The old cost of the flip: the two tets and the face between them.
    const int* fv = kFaceVertices[f];
    const VertexId* v = &ringScratch_[0];
    entry.zeroOldCost = n != kNoNeighbor &&
      (!cost.tet || (cost.tet(tetVertices(t)) == 0 && cost.tet(tetVertices(faceTet(n))) == 0)) &&
      (!cost.face || cost.face(v[fv[0]], v[fv[1]], v[fv[2]]) == 0);
  }
  if (gainOnly && entry.zeroOldCost)
    return false;
  if (!entry.built)
  {
    entry.built = true;
    entry.ok = flip23Candidate(mesh_, t, f, cost, entry.candidate);
  }
  if (entry.ok)
    out = entry.candidate;
  return entry.ok;
}

bool Recovery::cachedEdgeRemoval(TetId t,
  VertexId p,
  VertexId q,
  const FlipCost& cost,
  FlipCandidate& out,
  bool gainOnly)
{
  // The candidate depends only on the shell walked from t (its tet ids, which determine the
  // old tets, and its ring, which determines every tet priced): the same walk, the same
  // answer. Constrained flags do not change during a flip search.
  // Slot: t and the pair of local indices of p and q (0..5); the entry names the edge too.
  static constexpr int kPairSlot[4][4] = {
    { -1, 0, 1, 2 }, { 0, -1, 3, 4 }, { 1, 3, -1, 5 }, { 2, 4, 5, -1 }
  };
  const int ip = localIndex(mesh_, t, p), iq = localIndex(mesh_, t, q);
  if (ip < 0 || iq < 0 || ip == iq)
    return false;
  CachedCandidate& entry =
    edgeRemovalCache_.at(6 * static_cast<std::size_t>(t) + kPairSlot[ip][iq]);
  bool closed = edgeShell(mesh_, t, p, q, shellScratch_, ringScratch_);
  if (entry.clock == 0 || entry.p != p || entry.q != q || shellScratch_ != entry.shell ||
    ringScratch_ != entry.ring)
  {
    entry.clock = 1;
    entry.p = p;
    entry.q = q;
    entry.shell = shellScratch_;
    entry.ring = ringScratch_;
    entry.built = false;
    // The old cost of the removal: the edge, its faces and the tets of its shell.
    bool zero = closed && (!cost.edge || cost.edge(p, q) == 0);
    for (std::size_t k = 0; k < ringScratch_.size() && zero; ++k)
      zero = (!cost.face || cost.face(p, q, ringScratch_[k]) == 0) &&
        (!cost.tet || cost.tet(tetVertices(shellScratch_[k])) == 0);
    entry.zeroOldCost = zero;
    if (!closed)
    {
      entry.built = true;
      entry.ok = false;
    }
  }
  if (gainOnly && entry.zeroOldCost)
    return false;
  if (!entry.built)
  {
    entry.built = true;
    entry.ok = edgeRemovalCandidate(mesh_, p, q, entry.shell, entry.ring, cost, entry.candidate);
  }
  if (entry.ok)
    out = entry.candidate;
  return entry.ok;
}

void Recovery::replace(const std::vector<TetId>& oldTets,
  const std::vector<TetVertices>& newTets,
  std::vector<TetId>* created)
{
  replaceTets(mesh_, index_, oldTets, newTets, created);
  for (const TetVertices& t : newTets)
    for (VertexId v : t)
      touch(v);
}

void Recovery::recordFailure(Failure& failure, VertexId seed, const FlipCost& searchCost)
{
  std::vector<TetId> pipe, star;
  collectPipe(seed, searchCost, pipe);
  vertexStar(mesh_, index_, seed, star); // the search starts from the seed's star
  pipe.insert(pipe.end(), star.begin(), star.end());
  failure.vertices.clear();
  for (TetId t : pipe)
    for (int i = 0; i < 4; ++i)
      failure.vertices.push_back(mesh_.vertex(t, i));
  std::sort(failure.vertices.begin(), failure.vertices.end());
  failure.vertices.erase(
    std::unique(failure.vertices.begin(), failure.vertices.end()), failure.vertices.end());
  failure.clock = clock_ + 1; // valid: the clock never returns 0 after a change
}

bool Recovery::unchangedSince(const Failure& failure) const
{
  if (failure.clock == 0)
    return false;
  for (VertexId v : failure.vertices)
  {
    if (static_cast<std::size_t>(v) < vertexStamp_.size() && vertexStamp_[v] >= failure.clock)
      return false;
  }
  return true;
}

bool Recovery::interrupted()
{
  if (interrupted_)
    return true;
  auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - lastPoll_).count() < 0.05)
    return false;
  lastPoll_ = now;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  if (options_.maxSeconds > 0 && elapsed > options_.maxSeconds)
  {
    std::ostringstream error;
    error << "boundary recovery exceeded the time budget of " << options_.maxSeconds
          << " s while recovering " << currentItem_;
    result_.error = error.str();
    interrupted_ = true;
  }
  else if (progress_ && *progress_ && !(*progress_)(progressFraction_))
  {
    result_.error = "aborted during boundary recovery (while recovering " + currentItem_ + ")";
    interrupted_ = true;
  }
  return interrupted_;
}

bool Recovery::insertSteiner(const double* c, TetId tet)
{
  VertexId id = mesh_.addVertex(c[0], c[1], c[2]);
  InsertResult r = insertVertex(mesh_, id, tet, *workspace_);
  if (r.status != InsertStatus::Inserted)
  {
    mesh_.coords.resize(mesh_.coords.size() - 3);
    return false;
  }
  result_.steinerVertices.push_back(id);
  index_.note(r.tet, mesh_);
  std::vector<TetId> star;
  vertexStar(mesh_, index_, id, star);
  for (TetId t : star)
  {
    index_.note(t, mesh_);
    for (int i = 0; i < 4; ++i)
      touch(mesh_.vertex(t, i));
  }
  return true;
}

std::array<double, 6> Recovery::boxOf(std::initializer_list<VertexId> vertices) const
{
  std::array<double, 6> box;
  for (int k = 0; k < 3; ++k)
  {
    box[k] = point(*vertices.begin())[k];
    box[k + 3] = box[k];
    for (VertexId v : vertices)
    {
      box[k] = std::min(box[k], point(v)[k]);
      box[k + 3] = std::max(box[k + 3], point(v)[k]);
    }
  }
  return box;
}

ItemCost Recovery::edgeCost(VertexId a, VertexId b) const
{
  ItemCost c;
  c.box = boxOf({ a, b });
  c.segment[0] = a;
  c.segment[1] = b;
  c.tet = [this, a, b](const TetVertices& t)
  {
    const double* s[2] = { point(a), point(b) };
    return tetMeets(s, 2, t) ? 1 : 0;
  };
  c.face = [this, a, b](VertexId x, VertexId y, VertexId z)
  {
    return geometry::segmentMeetsTriangle(point(a), point(b), point(x), point(y), point(z)) ? 1 : 0;
  };
  c.edge = [this, a, b](VertexId u, VertexId v)
  { return geometry::segmentsCross(point(a), point(b), point(u), point(v)) ? 1 : 0; };
  return c;
}

ItemCost Recovery::edgeAndFacesCost(std::size_t e) const
{
  // The missing edge plus the input triangles around it: tets that straddle a planar part of
  // the surface next to the edge are obstacles too, and counting them lets flips (and Steiner
  // points near the middle of their crossing edges, far from the surface) clear them.
  std::vector<FlipCost> parts = { edgeCost(surface_.edges[e][0], surface_.edges[e][1]) };
  ItemCost c;
  c.box = boxOf({ surface_.edges[e][0], surface_.edges[e][1] });
  for (const auto& tri : edgeTriangles(e))
  {
    parts.push_back(faceCost(tri));
    const std::array<double, 6> box = boxOf({ tri[0], tri[1], tri[2] });
    for (int k = 0; k < 3; ++k)
    {
      c.box[k] = std::min(c.box[k], box[k]);
      c.box[k + 3] = std::max(c.box[k + 3], box[k + 3]);
    }
  }
  c.tet = [parts](const TetVertices& t)
  {
    int sum = 0;
    for (const FlipCost& part : parts)
      sum += part.tet ? part.tet(t) : 0;
    return sum;
  };
  c.face = [parts](VertexId x, VertexId y, VertexId z)
  {
    int sum = 0;
    for (const FlipCost& part : parts)
      sum += part.face ? part.face(x, y, z) : 0;
    return sum;
  };
  c.edge = [parts](VertexId u, VertexId v)
  {
    int sum = 0;
    for (const FlipCost& part : parts)
      sum += part.edge ? part.edge(u, v) : 0;
    return sum;
  };
  return c;
}

ItemCost Recovery::faceCost(const std::array<VertexId, 3>& tri) const
{
  ItemCost c;
  c.box = boxOf({ tri[0], tri[1], tri[2] });
  c.tet = [this, tri](const TetVertices& t)
  {
    const double* s[3] = { point(tri[0]), point(tri[1]), point(tri[2]) };
    return tetMeets(s, 3, t) ? 1 : 0;
  };
  c.edge = [this, tri](VertexId u, VertexId v)
  {
    return geometry::segmentMeetsTriangle(
             point(u), point(v), point(tri[0]), point(tri[1]), point(tri[2]))
      ? 1
      : 0;
  };
  return c;
}

int Recovery::tetCost(const FlipCost& cost, TetId t)
{
  TetVertices v = tetVertices(t);
  TetCostEntry* entry = nullptr;
  if (&cost == tetCostOwner_)
  {
    if (static_cast<std::size_t>(t) >= tetCostCache_.size())
      tetCostCache_.resize(2 * static_cast<std::size_t>(t) + 16);
    entry = &tetCostCache_[t];
    if (entry->epoch == tetCostEpoch_ && entry->vertices == v)
      return entry->cost;
  }
  int c = exactTetCost(cost, v);
  if (entry)
    *entry = { v, c, tetCostEpoch_ };
  return c;
}

int Recovery::exactTetCost(const FlipCost& cost, const TetVertices& v) const
{
  int c = cost.tet ? cost.tet(v) : 0;
  for (int f = 0; f < 4 && cost.face; ++f)
  {
    const int* fv = kFaceVertices[f];
    c += cost.face(v[fv[0]], v[fv[1]], v[fv[2]]);
  }
  for (int i = 0; i < 4 && cost.edge; ++i)
    for (int j = i + 1; j < 4; ++j)
      c += cost.edge(v[i], v[j]);
  return c;
}

void Recovery::collectPipe(VertexId seed,
  const FlipCost& cost,
  std::vector<TetId>& pipe,
  VertexId tip)
{
  std::vector<TetId>& star = starScratch_;
  vertexStar(mesh_, index_, seed, star);
  pipe.clear();
  if (++pipeEpoch_ == 0)
  {
    std::fill(pipeStamp_.begin(), pipeStamp_.end(), 0u);
    pipeEpoch_ = 1;
  }
  if (pipeStamp_.size() < static_cast<std::size_t>(mesh_.tetCapacity()))
    pipeStamp_.resize(2 * static_cast<std::size_t>(mesh_.tetCapacity()), 0u);
  auto visit = [&](TetId t)
  {
    if (static_cast<std::size_t>(t) >= pipeStamp_.size())
      pipeStamp_.resize(2 * static_cast<std::size_t>(t) + 16, 0u);
    if (pipeStamp_[t] == pipeEpoch_)
      return false;
    pipeStamp_[t] = pipeEpoch_;
    return true;
  };
  for (TetId t : star)
    visit(t);
  // In the search for an edge alone, seeded at its end a, most of a's star lies away from the
  // edge: three orientations at a rule a tet out, instead of pricing its 11 entities.
  // In the flip search the answers are cached per tet (its star is walked again for every
  // move); the refill of a cavity (tip given) walks each star once.
  const bool coneTest = &cost == tetCostOwner_ && seed == coneApex_;
  const VertexId coneEnd = coneTest ? coneTip_ : tip;
  auto segmentMisses = [&](const TetVertices& v)
  {
    const double* p[4] = { point(v[0]), point(v[1]), point(v[2]), point(v[3]) };
    const int i = v[0] == seed ? 0 : v[1] == seed ? 1 : v[2] == seed ? 2 : 3;
    return geometry::segmentFromVertexMissesTet(p, i, point(coneEnd));
  };
  for (TetId t : star)
  {
    if (coneTest)
    {
      const TetVertices v = tetVertices(t);
      if (static_cast<std::size_t>(t) >= coneCache_.size())
        coneCache_.resize(2 * static_cast<std::size_t>(t) + 16);
      ConeEntry& entry = coneCache_[t];
      if (entry.epoch != tetCostEpoch_ || entry.vertices != v)
        entry = { v, tetCostEpoch_, segmentMisses(v) };
      if (entry.misses)
        continue;
    }
    else if (coneEnd >= 0 && segmentMisses(tetVertices(t)))
      continue;
    if (tetCost(cost, t) > 0)
      pipe.push_back(t);
  }
  for (std::size_t k = 0; k < pipe.size(); ++k)
  {
    for (int f = 0; f < 4; ++f)
    {
      FaceRef n = mesh_.neighbor(pipe[k], f);
      if (n == kNoNeighbor || !visit(faceTet(n)))
        continue;
      if (tetCost(cost, faceTet(n)) > 0)
        pipe.push_back(faceTet(n));
    }
  }
}

int Recovery::findMoves(VertexId seed,
  const FlipCost& cost,
  std::vector<TetId>& pipe,
  FlipCandidate& best,
  bool& bestIsFlip23,
  std::vector<FlipCandidate>* neutral)
{
  collectPipe(seed, cost, pipe);
  FlipCandidate candidate;
  int bestGain = 0;
  best.minQuality = -1;
  auto& triedFaces = triedFaces_;
  auto& triedEdges = triedEdges_;
  triedFaces.clear();
  triedEdges.clear();
  auto consider = [&](bool isFlip23)
  {
    int gain = candidate.oldCost - candidate.newCost;
    if (gain == 0 && neutral)
    {
      // Keep only what lookahead tries: the kMaxNeutral best shaped, earlier first among
      // equals (= a stable sort by decreasing quality, truncated), without copying the rest.
      std::vector<FlipCandidate>& list = *neutral;
      std::size_t pos = list.size();
      while (pos > 0 && list[pos - 1].minQuality < candidate.minQuality)
        --pos;
      if (pos < kMaxNeutral)
      {
        if (list.size() < kMaxNeutral)
          list.emplace_back();
        std::rotate(list.begin() + pos, list.end() - 1, list.end());
        list[pos] = candidate;
      }
    }
    if (gain > bestGain || (gain == bestGain && gain > 0 && candidate.minQuality > best.minQuality))
    {
      bestGain = gain;
      best = candidate;
      bestIsFlip23 = isFlip23;
    }
  };
  for (TetId t : pipe)
  {
    TetVertices v = tetVertices(t);
    for (int f = 0; f < 4; ++f)
    {
      const int* fv = kFaceVertices[f];
      VertexId a = v[fv[0]], b = v[fv[1]], c = v[fv[2]];
      sort2(a, b);
      sort2(b, c);
      sort2(a, b);
      if (!triedFaces.insert({ a, b, c }))
        continue;
      if (cachedFlip23(t, f, cost, candidate, !neutral))
        consider(true);
    }
    for (int i = 0; i < 4; ++i)
    {
      for (int j = i + 1; j < 4; ++j)
      {
        if (isInputEdge(v[i], v[j]) ||
          !triedEdges.insert({ std::min(v[i], v[j]), std::max(v[i], v[j]) }))
          continue;
        if (cachedEdgeRemoval(t, v[i], v[j], cost, candidate, !neutral))
          consider(false);
      }
    }
  }
  return bestGain;
}

bool Recovery::lookahead(VertexId seed, const FlipCost& cost, std::vector<FlipCandidate>& neutral)
{
  // Try the neutral moves, best shaped first; keep one only if it enables a strictly
  // improving move (so the pair lowers the measure and the search still terminates).
  // (findMoves keeps them sorted that way and at most kMaxNeutral.)
  std::stable_sort(neutral.begin(),
    neutral.end(),
    [](const FlipCandidate& a, const FlipCandidate& b) { return a.minQuality > b.minQuality; });
  if (neutral.size() > kMaxNeutral)
    neutral.resize(kMaxNeutral);
  std::vector<TetId> created, pipe, star;
  FlipCandidate next;
  bool nextIsFlip23 = false;
  // Undoing a move restores the tets under other ids, so name them by their vertices.
  std::vector<std::vector<TetVertices>> oldVertices;
  for (const FlipCandidate& move : neutral)
  {
    oldVertices.emplace_back();
    for (TetId t : move.oldTets)
      oldVertices.back().push_back(tetVertices(t));
  }
  for (std::size_t m = 0; m < neutral.size(); ++m)
  {
    const std::vector<TetVertices>& old = oldVertices[m];
    std::vector<TetId> oldTets;
    for (std::size_t k = 0; k < old.size(); ++k)
    {
      const TetVertices& v = old[k];
      // The same id while no undo has renamed it (a tet is unique by its vertex tuple).
      const TetId id = neutral[m].oldTets[k];
      if (!mesh_.isDeleted(id) && tetVertices(id) == v)
      {
        oldTets.push_back(id);
        continue;
      }
      vertexStar(mesh_, index_, v[0], star);
      for (TetId t : star)
      {
        if (tetVertices(t) == v)
          oldTets.push_back(t);
      }
    }
    if (oldTets.size() != old.size())
      continue;
    replace(oldTets, neutral[m].newTets, &created);
    if (findMoves(seed, cost, pipe, next, nextIsFlip23, nullptr) > 0)
    {
      ++result_.neutralMoves;
      return true;
    }
    std::vector<TetId> undo = created;
    replace(undo, old);
  }
  return false;
}

bool Recovery::flipUntil(VertexId seed,
  const ItemCost& exactCost,
  const FlipCost& cost,
  const std::function<bool()>& done,
  std::size_t search)
{
  lastSearchCost_ = cost;
  flip23Cache_.clear();
  edgeRemovalCache_.clear();
  deep_.forgetCandidates(); // a new measure (and constrained faces may have been added)
  search_ = search;
  // An edge alone, seeded at one of its ends: collectPipe's cone test applies.
  const VertexId* segment = exactCost.segment;
  coneApex_ = seed == segment[0] || seed == segment[1] ? seed : -1;
  coneTip_ = seed == segment[0] ? segment[1] : segment[0];
  ++tetCostEpoch_; // forget the cached tet costs and cone tests (in O(1))
  tetCostOwner_ = &cost;
  struct OwnerReset
  {
    const FlipCost*& owner;
    ~OwnerReset() { owner = nullptr; }
  } ownerReset{ tetCostOwner_ };
  std::vector<TetId> pipe;
  std::vector<FlipCandidate> neutral;
  for (int move = 0; move < options_.maxMovesPerItem; ++move)
  {
    if (done())
      return true;
    if (interrupted())
      return false;
    FlipCandidate best;
    bool bestIsFlip23 = false;
    if (findMoves(seed, cost, pipe, best, bestIsFlip23, nullptr) > 0)
    {
      replace(best.oldTets, best.newTets);
      if (bestIsFlip23)
        ++result_.flips23;
      else
        ++result_.edgeRemovals;
      continue;
    }
    // No move helps directly: remove an edge that cuts the item by a sequence of flips (the
    // wrong diagonal of a planar quad needs that), else shrink the shell of such an edge, so
    // that a later edge removal can take it out, or look one neutral move ahead.
    bool moved = false;
    if (removeCrossingDeep(pipe, cost, done, moved))
      continue;
    if (moved)
      collectPipe(seed, cost, pipe); // the attempts were undone, the tets came back renamed
    if (shrinkCrossingShell(pipe, cost))
      continue;
    // The cost-neutral moves, which the search for gains skipped.
    neutral.clear();
    findMoves(seed, cost, pipe, best, bestIsFlip23, &neutral);
    if (lookahead(seed, cost, neutral))
      continue;
    return false;
  }
  return done();
}

bool Recovery::shrinkCrossingShell(const std::vector<TetId>& pipe, const FlipCost& cost)
{
  FlipCandidate best, candidate;
  bool found = false;
  ScratchSet<std::array<VertexId, 2>>& triedEdges = edgeScratch_;
  triedEdges.clear();
  std::vector<TetId>& shell = shellScratch2_;
  std::vector<VertexId>& ring = ringScratch2_;
  for (TetId t : pipe)
  {
    TetVertices v = tetVertices(t);
    for (int i = 0; i < 4; ++i)
    {
      for (int j = i + 1; j < 4; ++j)
      {
        if (isInputEdge(v[i], v[j]) ||
          !triedEdges.insert({ std::min(v[i], v[j]), std::max(v[i], v[j]) }) ||
          cost.edge(v[i], v[j]) == 0 || !edgeShell(mesh_, t, v[i], v[j], shell, ring))
          continue;
        // Face (p,q,ring[k]) separates shell[k-1] from shell[k]; a 2-3 flip of it takes
        // ring[k] out of the ring.
        const int n = static_cast<int>(ring.size());
        for (int k = 0; k < n && n > 3; ++k)
        {
          TetId s = shell[k];
          int f = localIndex(mesh_, s, ring[(k + 1) % n]);
          if (!cachedFlip23(s, f, cost, candidate) || candidate.newCost > candidate.oldCost)
            continue;
          if (!found || betterMove(candidate, best))
          {
            best = candidate;
            found = true;
          }
        }
      }
    }
  }
  if (!found)
    return false;
  replace(best.oldTets, best.newTets);
  ++result_.flips23;
  return true;
}

bool Recovery::removeCrossingDeep(const std::vector<TetId>& pipe,
  const FlipCost& cost,
  const std::function<bool()>& done,
  bool& moved)
{
  // Link levels (1: flip the blocking link edge by plain moves; 2: one more level) and moves
  // per attempt: enough for the wrong diagonal of a planar quad, whose shell has 5-6 tets.
  constexpr int kLevels = 2, kBudget = 32;
  std::vector<std::array<VertexId, 2>> crossing;
  ScratchSet<std::array<VertexId, 2>>& seen = edgeScratch_;
  seen.clear();
  for (TetId t : pipe)
  {
    TetVertices v = tetVertices(t);
    for (int i = 0; i < 4; ++i)
    {
      for (int j = i + 1; j < 4; ++j)
      {
        if (seen.insert({ std::min(v[i], v[j]), std::max(v[i], v[j]) }) &&
          cost.edge(v[i], v[j]) > 0 && !isInputEdge(v[i], v[j]))
          crossing.push_back({ v[i], v[j] });
      }
    }
  }
  // Deep removals stamp nothing while they run: one that is undone leaves the same tets, and
  // one that is kept stamps everything it changed at once.
  DeepEdgeRemoval::Journal& journal = deep_.journal;
  deep_.resetJournal();
  std::vector<VertexId> examined;
  deep_.seen = &examined;
  for (const auto& edge : crossing)
  {
    const auto failures = deepFailuresBySearch_.find(search_);
    if (failures != deepFailuresBySearch_.end())
    {
      const auto failed = failures->second.find(edgeKey(edge[0], edge[1]));
      if (failed != failures->second.end() && unchangedSince(failed->second))
        continue;
    }
    int budget = kBudget;
    examined.clear();
    const bool removed = deep_.remove(edge[0], edge[1], kLevels, cost, budget);
    moved = moved || journal.moves > 0;
    if (removed && (journal.delta < 0 || done()))
    {
      deep_.seen = nullptr;
      for (const auto& entry : journal.entries)
      {
        for (const auto* tets : { &entry.old, &entry.created })
          for (const TetVertices& v : *tets)
            for (VertexId x : v)
              touch(x);
      }
      for (const auto& entry : journal.entries)
        ++(entry.old.size() == 2 && entry.created.size() == 3 ? result_.flips23
                                                              : result_.edgeRemovals);
      deep_.resetJournal();
      return true;
    }
    deep_.undoTo(0, 0);
    // The attempt was undone (no stamps): it would fail the same way until one of the
    // vertices it examined gets a changed tet.
    Failure& failure = deepFailuresBySearch_[search_][edgeKey(edge[0], edge[1])];
    std::sort(examined.begin(), examined.end());
    examined.erase(std::unique(examined.begin(), examined.end()), examined.end());
    failure.vertices = examined;
    failure.clock = clock_ + 1;
  }
  deep_.seen = nullptr;
  return false;
}

bool Recovery::onInputSurface(const double* x, double tolerance) const
{
  for (const std::int32_t i : trianglesNear({ x[0], x[1], x[2], x[0], x[1], x[2] }, tolerance))
  {
    const auto& box = triangleBoxes_[static_cast<std::size_t>(i)];
    if (x[0] < box[0] - tolerance || x[1] < box[1] - tolerance || x[2] < box[2] - tolerance ||
      x[0] > box[3] + tolerance || x[1] > box[4] + tolerance || x[2] > box[5] + tolerance)
      continue;
    const auto& t = surface_.triangles[static_cast<std::size_t>(i)];
    if (geometry::pointOnTriangle(x, point(t[0]), point(t[1]), point(t[2])) ||
      geometry::pointTriangleDistanceSquared(x, point(t[0]), point(t[1]), point(t[2])) <
        tolerance * tolerance)
      return true;
  }
  return false;
}

bool Recovery::insertSteinerNear(VertexId seed, const ItemCost& exactCost)
{
  const FlipCost cost = memoized(exactCost, mesh_, emptyMemo());
  std::vector<TetId> pipe;
  collectPipe(seed, cost, pipe);
  // Candidate positions, best first. (1) Next to the middle of an edge that cuts the item,
  // inside a tet around it: every tet around an edge has the edge's midpoint strictly inside
  // its circumsphere, so the insertion cavity swallows the whole shell and the edge is gone
  // (the fix for coplanar crossings, e.g. the wrong diagonal of a square face). (2) The
  // centroid of a tet the item cuts through, from the middle of the pipe outwards; (3) of any
  // pipe tet.
  struct Candidate
  {
    TetId tet;
    VertexId p, q; // edge to approach, or -1
  };
  std::vector<Candidate> order;
  std::set<std::uint64_t> seen;
  std::vector<TetId> shell;
  std::vector<VertexId> ring;
  for (TetId t : pipe)
  {
    TetVertices v = tetVertices(t);
    for (int i = 0; i < 4; ++i)
    {
      for (int j = i + 1; j < 4; ++j)
      {
        if (!seen.insert(edgeKey(v[i], v[j])).second || cost.edge(v[i], v[j]) == 0)
          continue;
        if (!edgeShell(mesh_, t, v[i], v[j], shell, ring))
          shell = { t };
        for (TetId s : shell)
          order.push_back({ s, v[i], v[j] });
      }
    }
  }
  std::size_t nearEdges = order.size();
  for (int pass = 0; pass < 2; ++pass)
  {
    std::size_t first = order.size();
    for (TetId t : pipe)
    {
      if ((cost.tet(tetVertices(t)) > 0) == (pass == 0))
        order.push_back({ t, -1, -1 });
    }
    std::rotate(
      order.begin() + first, order.begin() + first + (order.size() - first) / 2, order.end());
  }
  std::rotate(order.begin(), order.begin() + nearEdges / 2, order.begin() + nearEdges);
  for (const Candidate& candidate : order)
  {
    TetVertices v = tetVertices(candidate.tet);
    const double* p[4] = { point(v[0]), point(v[1]), point(v[2]), point(v[3]) };
    double c[3];
    for (int k = 0; k < 3; ++k)
    {
      c[k] = 0.25 * (p[0][k] + p[1][k] + p[2][k] + p[3][k]);
      if (candidate.p >= 0)
        c[k] = 0.2 * c[k] + 0.4 * (point(candidate.p)[k] + point(candidate.q)[k]);
    }
    // Flat tets on planar parts of the surface put c within rounding of a face, and each such
    // point makes a flatter tet for the next (gear.vtp: 1.6e-6, 7.8e-8, ... down to 5.6e-17):
    // refused at 1e-6 of the tet's longest edge, which stops that at the first.
    double longest = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        longest = std::max(longest,
          (p[i][0] - p[j][0]) * (p[i][0] - p[j][0]) + (p[i][1] - p[j][1]) * (p[i][1] - p[j][1]) +
            (p[i][2] - p[j][2]) * (p[i][2] - p[j][2]));
    if (!geometry::pointInsideTet(c, p) || onInputSurface(c, 1e-6 * std::sqrt(longest)))
      continue;
    if (insertSteiner(c, candidate.tet))
      return true;
  }
  return false;
}

bool Recovery::refillEdgeCavity(std::size_t e, const FlipCost& cost, int maxTets)
{
  const VertexId ends[2] = { surface_.edges[e][0], surface_.edges[e][1] };
  auto keep = [this](VertexId u, VertexId v) { return isInputEdge(u, v); };
  std::vector<TetId> cavity;
  std::vector<TetVertices> cone;
  for (int k = 0; k < 2; ++k)
  {
    collectPipe(ends[k], cost, cavity, ends[1 - k]);
    if (cavity.empty() ||
      !coneFromVertex(mesh_, ends[k], cavity, keep, CavityConeLimits{ maxTets }, cone))
      continue;
    const VertexId other = ends[1 - k];
    if (std::none_of(cone.begin(),
          cone.end(),
          [other](const TetVertices& c)
          { return c[0] == other || c[1] == other || c[2] == other || c[3] == other; }))
      continue;
    replace(cavity, cone, nullptr);
    ++result_.cavityCones;
    return true;
  }
  return false;
}

std::vector<std::size_t> Recovery::itemTriangles(std::size_t key) const
{
  const auto& triangles = surface_.triangles;
  std::vector<std::size_t> mine;
  if (key >= surface_.edges.size())
    mine.push_back(key - surface_.edges.size());
  else
  {
    const VertexId a = surface_.edges[key][0], b = surface_.edges[key][1];
    // a's triangles, each once (one listing a twice is there twice), as a scan would pick them.
    for (std::int32_t k = vertexTriangleStart_[a]; k < vertexTriangleStart_[a + 1]; ++k)
    {
      const std::size_t i = static_cast<std::size_t>(vertexTriangles_[static_cast<std::size_t>(k)]);
      const auto& t = triangles[i];
      if ((mine.empty() || mine.back() != i) &&
        std::count(t.begin(), t.end(), a) + std::count(t.begin(), t.end(), b) == 2)
        mine.push_back(i);
    }
  }
  return mine;
}

std::string Recovery::nearlyTouchingTriangles(std::size_t key) const
{
  const auto& triangles = surface_.triangles;
  auto longestEdge = [](const double* const v[3])
  {
    double longest2 = 0;
    for (int k = 0; k < 3; ++k)
    {
      double d2 = 0;
      for (int c = 0; c < 3; ++c)
        d2 += (v[k][c] - v[(k + 1) % 3][c]) * (v[k][c] - v[(k + 1) % 3][c]);
      longest2 = std::max(longest2, d2);
    }
    return std::sqrt(longest2);
  };
  for (std::size_t i : itemTriangles(key))
  {
    const auto& t = triangles[i];
    const double* p[3] = { point(t[0]), point(t[1]), point(t[2]) };
    const auto& box = triangleBoxes_[i];
    const double sizeI = longestEdge(p);
    if (largestTriangle_ < 0)
      for (const auto& u : triangles)
      {
        const double* q[3] = { point(u[0]), point(u[1]), point(u[2]) };
        largestTriangle_ = std::max(largestTriangle_, longestEdge(q));
      }
    const double margin = options_.nearTouchRatio * std::max(sizeI, largestTriangle_);
    for (const std::int32_t near : trianglesNear(box, margin))
    {
      const std::size_t j = static_cast<std::size_t>(near);
      const auto& u = triangles[j];
      const double* q[3] = { point(u[0]), point(u[1]), point(u[2]) };
      const double size = std::max(sizeI, longestEdge(q));
      const double tolerance = options_.nearTouchRatio * size;
      const auto& other = triangleBoxes_[j];
      bool apart = j == i;
      for (int k = 0; k < 3 && !apart; ++k)
        apart = box[k] > other[k + 3] + tolerance || other[k] > box[k + 3] + tolerance;
      if (apart)
        continue;
      // Shared vertices touch by construction: measure only the parts away from them (the
      // vertices of each triangle that the other lacks, against the other triangle).
      const int shared = static_cast<int>(std::count(u.begin(), u.end(), t[0]) +
        std::count(u.begin(), u.end(), t[1]) + std::count(u.begin(), u.end(), t[2]));
      double gap2 = std::numeric_limits<double>::infinity();
      if (shared == 0)
        gap2 = geometry::triangleDistanceSquared(p, q);
      else
        for (int k = 0; k < 3; ++k)
        {
          if (std::count(u.begin(), u.end(), t[k]) == 0)
            gap2 = std::min(gap2, geometry::pointTriangleDistanceSquared(p[k], q[0], q[1], q[2]));
          if (std::count(t.begin(), t.end(), u[k]) == 0)
            gap2 = std::min(gap2, geometry::pointTriangleDistanceSquared(q[k], p[0], p[1], p[2]));
        }
      const double gap = std::sqrt(gap2);
      if (!(gap <= tolerance))
        continue;
      std::ostringstream out;
      out << "input triangles " << std::min(i, j) << " and " << std::max(i, j);
      if (gap > 0)
        out << " come within " << gap << " of each other (" << gap / size << " of their size)";
      else
        out << " touch to double precision without intersecting exactly";
      return out.str();
    }
  }
  return {};
}

std::string Recovery::intersectingTriangles(std::size_t key) const
{
  const auto& triangles = surface_.triangles;
  const std::vector<std::size_t> mine = itemTriangles(key);
  auto overlap = [](const std::array<double, 6>& x, const std::array<double, 6>& y)
  {
    for (int k = 0; k < 3; ++k)
      if (x[k] > y[k + 3] || y[k] > x[k + 3])
        return false;
    return true;
  };
  for (std::size_t i : mine)
  {
    const auto& t = triangles[i];
    const double* p[3] = { point(t[0]), point(t[1]), point(t[2]) };
    if (isTriangleDegenerate(p[0], p[1], p[2]))
      continue;
    for (const std::int32_t near : trianglesNear(triangleBoxes_[i], 0))
    {
      const std::size_t j = static_cast<std::size_t>(near);
      const auto& u = triangles[j];
      if (j == i || !overlap(triangleBoxes_[i], triangleBoxes_[j]))
        continue;
      const double* q[3] = { point(u[0]), point(u[1]), point(u[2]) };
      if (isTriangleDegenerate(q[0], q[1], q[2]) ||
        !trianglesIntersectImproperly(p, t.data(), q, u.data()))
        continue;
      std::ostringstream out;
      out << "input triangles " << std::min(i, j) << " and " << std::max(i, j) << " intersect";
      return out.str();
    }
  }
  return {};
}

void Recovery::markConstrained(FaceRef face)
{
  TetId t = faceTet(face);
  int f = faceIndex(face);
  mesh_.setConstrained(t, f, true);
  for (int i = 0; i < 4; ++i)
  {
    if (i != f)
      touch(mesh_.vertex(t, i));
  }
  FaceRef n = mesh_.neighbor(t, f);
  if (n != kNoNeighbor)
    mesh_.setConstrained(faceTet(n), faceIndex(n), true);
}

void Recovery::findPresentItems(std::vector<char>& edgeInMesh, std::vector<FaceRef>& triangleFace)
{
  const VertexId pointCount = surface_.pointCount;
  edgeInMesh.assign(surface_.edges.size(), 0);
  triangleFace.assign(surface_.triangles.size(), -1);
  const TriangleIndex triangles(surface_.triangles);
  for (TetId t = 0; t < mesh_.tetCapacity(); ++t)
  {
    if (mesh_.isDeleted(t))
      continue;
    const TetVertices v = tetVertices(t);
    for (int f = 0; f < 4; ++f)
    {
      const int* fv = kFaceVertices[f];
      const FaceRef n = mesh_.neighbor(t, f);
      if (v[fv[0]] >= pointCount || v[fv[1]] >= pointCount || v[fv[2]] >= pointCount ||
        (n != kNoNeighbor && faceTet(n) < t))
        continue; // a box corner or a Steiner point, or the face seen from its other side
      const std::int32_t i = triangles.find(v[fv[0]], v[fv[1]], v[fv[2]]);
      if (i >= 0)
        triangleFace[i] = makeFaceRef(t, f);
    }
  }
  // The edges of those triangles (an edge whose triangles are all missing is looked up when
  // needed).
  for (std::size_t i = 0; i < triangleFace.size(); ++i)
    if (triangleFace[i] >= 0)
      for (int k = 0; k < 3; ++k)
      {
        const auto& tri = surface_.triangles[i];
        edgeInMesh[inputEdgeIndex(tri[k], tri[(k + 1) % 3])] = 1;
      }
}

RecoveryResult Recovery::run(const std::function<bool(double)>& progress)
{
  const auto& triangles = surface_.triangles;
  const auto& edges = surface_.edges;
  std::vector<char> recovered(triangles.size(), 0);
  std::size_t recoveredCount = 0;
  progress_ = &progress;
  failures_.assign(edges.size() + triangles.size(), Failure());
  // An edge found at clock c is still there while no tet incident to its first vertex has
  // been created or deleted since (every such change stamps all the tet's vertices).
  std::vector<std::uint64_t> edgeFoundAt(edges.size(), 0);
  // What the mesh has now: an item is still there while no tet at its first vertex changed
  // (edges), or while the tet found holds it (triangles). Each item's first look-up then
  // does what findEdge and findFace do besides searching: index_.tetOf repairs the index
  // (a rebuild when stale), which decides where later star searches start.
  std::vector<char> edgeInitially;
  std::vector<FaceRef> triangleInitially;
  findPresentItems(edgeInitially, triangleInitially);
  const std::uint64_t initialClock = clock_;
  auto unchangedAt = [&](VertexId a, std::uint64_t since)
  { return static_cast<std::size_t>(a) >= vertexStamp_.size() || vertexStamp_[a] < since; };
  // Edges of recovered triangles stay: constrained faces are never flipped or swallowed.
  std::vector<char> edgeSecured(edges.size(), 0);
  auto edgePresent = [&](std::size_t e)
  {
    VertexId a = edges[e][0];
    if (edgeSecured[e])
    {
      index_.tetOf(mesh_, a);
      return true;
    }
    if (edgeFoundAt[e] > 0 && unchangedAt(a, edgeFoundAt[e]))
      return true;
    if (edgeInitially[e])
    {
      edgeInitially[e] = 0;
      if (unchangedAt(a, initialClock + 1))
      {
        index_.tetOf(mesh_, a);
        edgeFoundAt[e] = clock_ + 1;
        return true;
      }
    }
    if (findEdge(mesh_, index_, a, edges[e][1]) < 0)
      return false;
    edgeFoundAt[e] = clock_ + 1;
    return true;
  };
  auto edgeName = [&](std::size_t e)
  {
    std::ostringstream name;
    name << "input edge (" << edges[e][0] << "," << edges[e][1] << ") of triangle "
         << surface_.edgeFirstTriangle[e];
    return name.str();
  };
  // Directional flips (DirectionalEdgeRecovery.h), then the refill of a small cavity by a cone
  // (CavityCone.h), then the flip search for input edge e: by the edge alone, then (withFaces)
  // with its triangles. True when the edge is in the mesh; else the failure is recorded
  // (unless interrupted). The directional flips recover about half of the edges missing from
  // CAD parts' Delaunay meshes at a few microseconds each, where the flip search took 40-60
  // (anchor.off, turbine.off, gear.vtp; 2026-11-30). The cone shares the search's memoized
  // measure (its pipe is the search's first), and takes many of the edges whose search would
  // fail at 0.2-0.7 ms. The search with the triangles runs only just before an edge's Steiner
  // point (2026-12-02): in the rounds' sweeps too it cost 5-13% of the boundary mesh's time on
  // anchor, dragknob, joint and gear and recovered almost nothing there, but without it before
  // the Steiner points the full pipeline's Q min fell on several surfaces (helix_tube 0.277 ->
  // 0.221, couplingdown 0.039 -> 0.029; work log).
  constexpr int kQuickConeTets = 48;
  auto keepEdge = [this](VertexId p, VertexId q) { return isInputEdge(p, q); };
  auto applyMove = [this](const FlipCandidate& move, bool isFlip23)
  {
    replace(move.oldTets, move.newTets);
    ++(isFlip23 ? result_.flips23 : result_.edgeRemovals);
  };
  auto flipToEdge = [&](std::size_t e, bool withFaces)
  {
    const VertexId a = edges[e][0], b = edges[e][1];
    auto exists = [&] { return edgePresent(e); };
    currentItem_ = edgeName(e);
    if (flipEdgeIntoMesh(mesh_, index_, a, b, keepEdge, applyMove) && exists())
      return true;
    const ItemCost alone = edgeCost(a, b);
    const FlipCost cost = memoized(alone, mesh_, emptyMemo());
    if (options_.refillCavities && refillEdgeCavity(e, cost, kQuickConeTets) && exists())
      return true;
    if (flipUntil(a, alone, cost, exists, 2 * e))
      return true;
    if (!interrupted_ && withFaces && flipUntil(a, edgeAndFacesCost(e), exists, 2 * e + 1))
      return true;
    if (!interrupted_)
      recordFailure(failures_[e], a, lastSearchCost_);
    return false;
  };
  auto triangleName = [&](std::size_t i)
  {
    const auto& t = triangles[i];
    std::ostringstream name;
    name << "input triangle " << i << " (" << t[0] << "," << t[1] << "," << t[2] << ")";
    return name.str();
  };
  // Reports progress (and honours an abort) once per round and every 1024 items.
  auto keepGoing = [&](std::size_t item)
  {
    if (!progress || item % 1024 != 0)
      return true;
    if (progress(static_cast<double>(recoveredCount) / triangles.size()))
      return true;
    result_.error = "aborted during boundary recovery";
    return false;
  };
  for (int round = 0;; ++round)
  {
    result_.rounds = round + 1;
    if (!keepGoing(0))
      return result_;
    for (std::size_t e = 0; e < edges.size(); ++e)
    {
      if (!keepGoing(e + 1))
        return result_;
      if (edgePresent(e) || unchangedSince(failures_[e]))
        continue;
      // The sweeps search by the edge alone; the search with its triangles runs just before
      // its Steiner point (see flipToEdge). Round 0 alone first (2026-11-29): over Data/ and
      // TetGen's test models recovery 4.48 -> 4.09 s, Steiner points 447 -> 425.
      flipToEdge(e, false);
      if (interrupted_)
        return result_;
    }
    for (std::size_t i = 0; i < triangles.size(); ++i)
    {
      if (!keepGoing(i + 1))
        return result_;
      if (recovered[i])
        continue;
      const auto& t = triangles[i];
      FaceRef face = -1;
      if (triangleInitially[i] >= 0 && faceHolds(triangleInitially[i], t))
      {
        index_.tetOf(mesh_, t[0]);
        face = triangleInitially[i];
      }
      else
        face = findFace(mesh_, index_, t[0], t[1], t[2]);
      triangleInitially[i] = -1;
      bool edgesPresent = true;
      for (int e = 0; e < 3 && face < 0 && edgesPresent; ++e)
        edgesPresent = findEdge(mesh_, index_, t[e], t[(e + 1) % 3]) >= 0;
      if (face < 0 && edgesPresent && !unchangedSince(failures_[edges.size() + i]))
      {
        currentItem_ = triangleName(i);
        auto exists = [&]
        {
          face = findFace(mesh_, index_, t[0], t[1], t[2]);
          return face >= 0;
        };
        if (!flipUntil(t[0], faceCost(t), exists, 2 * edges.size() + i) && !interrupted_)
          recordFailure(failures_[edges.size() + i], t[0], lastSearchCost_);
        if (interrupted_)
          return result_;
      }
      if (face >= 0)
      {
        markConstrained(face);
        for (int k = 0; k < 3; ++k)
          edgeSecured[inputEdgeIndex(t[k], t[(k + 1) % 3])] = 1;
        recovered[i] = 1;
        ++recoveredCount;
        progressFraction_ = static_cast<double>(recoveredCount) / triangles.size();
      }
    }
    if (recoveredCount == triangles.size())
    {
      result_.ok = true;
      return result_;
    }
    // Flips are stuck: one Steiner point near each item still missing (missing edges first,
    // since faces need their edges), then the next round retries the flips. Items are looked
    // up again just before, as work on other items may have recovered them meanwhile.
    int inserted = 0;
    // A missing edge is refilled by a cone where possible (no new point), which counts as
    // one of its Steiner points for the bounds below.
    auto refilled = [&](std::size_t key)
    {
      if (key >= edges.size() || !options_.refillCavities)
        return false;
      const CavityConeLimits defaults; // 256 tets: the last try before a point
      return refillEdgeCavity(key,
        memoized(edgeCost(edges[key][0], edges[key][1]), mesh_, emptyMemo()),
        defaults.maxTets);
    };
    auto steinerFor =
      [&](std::size_t key, const std::string& name, VertexId seed, const ItemCost& cost)
    {
      currentItem_ = name;
      if (interrupted())
        return false;
      int& count = steinerPerItem_[key];
      // Unchecked input: once the item looks stuck, or when it fails, name an intersecting pair.
      const int probeAt = options_.intersectionProbeAfter;
      std::string crossing = probeAt > 0 && count == probeAt ? intersectingTriangles(key) : "";
      // Any input: an item that needs many Steiner points near triangles that nearly touch
      // (closer than doubles can place points between, relative to their size) would only
      // fail slowly after maxSteinerPerItem of them: name the pair now.
      if (crossing.empty() && count == options_.nearTouchProbeAfter)
      {
        const std::string touching = nearlyTouchingTriangles(key);
        if (!touching.empty())
        {
          result_.error =
            "could not recover " + name + ": " + touching + " (nearly self-intersecting input)";
          return false;
        }
      }
      if (crossing.empty())
      {
        if (count >= options_.maxSteinerPerItem)
          result_.error = "could not recover " + name + " with " + std::to_string(count) +
            " Steiner points near it (self-intersecting or nearly degenerate input?)";
        else if (static_cast<int>(result_.steinerVertices.size()) >= options_.maxSteinerPoints)
          result_.error = "could not recover " + name + " within the budget of " +
            std::to_string(options_.maxSteinerPoints) + " Steiner points";
        else if (!refilled(key) && !insertSteinerNear(seed, cost))
          result_.error =
            "could not recover " + name + ": no Steiner point could be placed near it";
        else
        {
          ++count;
          ++inserted;
          return true;
        }
        if (probeAt > 0 && count != probeAt)
          crossing = intersectingTriangles(key);
      }
      if (!crossing.empty())
        result_.error = "could not recover " + name + ": " + crossing +
          " (self-intersecting input, which the input check would have named)";
      return false;
    };
    // An item that already took kSteinerRamp points gets count / 4 more per round: each round
    // reruns the flip searches of every missing item, so a hopeless item (nearly touching
    // triangles) then fails after about 20 rounds instead of maxSteinerPerItem.
    constexpr int kSteinerRamp = 8;
    auto burst = [&](std::size_t key)
    {
      const int count = steinerPerItem_[key];
      return count < kSteinerRamp ? 1 : count / 4;
    };
    for (std::size_t e = 0; e < edges.size(); ++e)
    {
      VertexId a = edges[e][0], b = edges[e][1];
      for (int k = burst(e); k > 0 && !edgePresent(e); --k)
      {
        // Steiner points placed since the flip search failed (for other items this round)
        // may have freed its flips: search again before placing one for this edge.
        if (!unchangedSince(failures_[e]))
        {
          if (flipToEdge(e, true))
            break;
          if (interrupted_)
            return result_;
        }
        // Alternate between placing the point against the edge alone and against the edge
        // and its triangles (which reaches tets straddling a planar part of the surface).
        bool alone = steinerPerItem_[e] % 2 == 0;
        if (!steinerFor(e, edgeName(e), a, alone ? edgeCost(a, b) : edgeAndFacesCost(e)))
          return result_;
      }
    }
    for (std::size_t i = 0; i < triangles.size() && inserted == 0; ++i)
    {
      const auto& t = triangles[i];
      const std::size_t key = edges.size() + i;
      for (int k = burst(key); k > 0; --k)
      {
        if (recovered[i] || findFace(mesh_, index_, t[0], t[1], t[2]) >= 0)
          break;
        if (!steinerFor(key, triangleName(i), t[0], faceCost(t)))
          return result_;
      }
    }
  }
}

} // namespace

RecoveryResult recoverBoundary(TetMesh& mesh,
  const SurfaceInput& surface,
  const RecoveryOptions& options,
  const std::function<bool(double)>& progress)
{
  Recovery recovery(mesh, surface, options);
  return recovery.run(progress);
}

} // namespace tetmesher
