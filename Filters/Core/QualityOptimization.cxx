// The driver of the quality optimiser: worst elements first, edge removal and multi-face
// removal (EdgeRemoval.h, MultiFaceRemoval.h) and vertex smoothing (VertexSmoothing.h), all
// judged by the rule of OptimizationContext.h.
#include "QualityOptimization.h"

#include "EdgeRemoval.h"
#include "EpochHashTable.h"
#include "MedianSplit.h"
#include "MultiFaceRemoval.h"
#include "OptimizationContext.h"
#include "ParallelPair.h"
#include "SurfaceInput.h"
#include "VertexInsertion.h"
#include "VertexSmoothing.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <utility>

namespace tetmesher
{
namespace
{
using namespace optimization;

// The dihedral stage works on tets below this multiple of OptimizationOptions::dihedralTarget.
constexpr double kDihedralWorkMargin = 1.2;
// The least bound on a pass's smoothing moves (OptimizationOptions::
// smoothingMovesPerFreeVertex): small meshes, where moves cost little, and meshes with few
// free vertices (a thin plate; vertices added by insertion) are not held back.
constexpr std::int64_t kMinSmoothingMoveBudget = 1000;
// Vertex insertion grows its cavity up to kCavity tets, and up to kWideCavity at a nearly
// flat tet (score below kFlatScore): a flat tet over two nearly coplanar surface triangles in
// a thin part of the body needs a cavity reaching across it (rotor_small.off: Q min 0.000
// with 16, 0.018 with 64; 2026-11-30). The wider search sees every cavity the narrow one does.
constexpr int kCavity = 16;
constexpr double kFlatScore = 0.01;
constexpr int kWideCavity = 64;

// True when t is below ctx's target, or a face neighbour that ctx owns is. (A half reads only
// its own tets' qualities: a tet with a vertex of the other half is measured, and its cache
// entry written, by whichever context owns it.)
bool badOrNextToBad(const Context& ctx, TetId t)
{
  if (ctx.quality(t).score < ctx.options.qualityTarget)
    return true;
  for (int f = 0; f < 4; ++f)
  {
    const FaceRef n = ctx.mesh.neighbor(t, f);
    if (n == kNoNeighbor)
      continue;
    const TetId u = faceTet(n);
    if (ctx.ownsTet(u) && ctx.quality(u).score < ctx.options.qualityTarget)
      return true;
  }
  return false;
}

class Optimizer
{
public:
  Optimizer(RegionMesh& rm, const OptimizationOptions& options, const std::vector<double>* h)
    : ctx_(rm, options, h)
  {
    main_.ctx = &ctx_;
    main_.edgeFailed = &edgeFailed_;
    main_.tetFailed = &tetFailed_;
    main_.reportsProgress = true;
  }
  // Starts from the quality cache of `previous`, which ran on the same mesh (and whose
  // sizes this one was given): the next stage does not measure every tet again.
  void continueFrom(Optimizer& previous)
  {
    ctx_.adoptCache(previous.ctx_);
    // The previous stage's memos, emptied: their slots are in use already.
    edgeFailed_ = std::move(previous.edgeFailed_);
    edgeFailed_.clear();
    main_.edgeFailed = &edgeFailed_;
    tetFailed_ = std::move(previous.tetFailed_);
    tetFailed_.clear();
    main_.tetFailed = &tetFailed_;
    insertFailed_ = std::move(previous.insertFailed_);
    insertFailed_.clear();
  }

  OptimizationResult run(const std::function<bool(double)>& progress);
  // The statistics that the caller takes from elsewhere are not gathered (a scan of every
  // tet each, ~2 ms at 200k tets): the first stage's "after" when a second stage follows
  // (its summarizeAfter(r, later) gives them), and both of the second stage's.
  void skipSummaries(bool before, bool after)
  {
    summaryBefore_ = !before;
    summaryAfter_ = !after;
  }
  // The size field, grown by the vertices this optimizer inserted (null without one).
  const std::vector<double>* sizes() const { return ctx_.size; }
  // Recomputes the "after" statistics (Q, dihedral, share below this optimizer's target)
  // after `later` (the next stage, with the sizes grown by its inserted vertices) changed
  // the mesh: from its cache, which covers every live tet at its end.
  void summarizeAfter(OptimizationResult& r, Optimizer& later)
  {
    if (later.ctx_.size && ctx_.size)
      ctx_.sizeCopy = later.ctx_.sizeCopy;
    ctx_.adoptCache(later.ctx_);
    summarizeAfter(r);
  }

private:
  using BadList = std::vector<std::pair<double, TetId>>; // (score, tet), worst first
  using EdgeMemo = EpochHashTable<std::uint64_t, std::uint64_t, MixHash64>;
  // When the search at a tet slot last failed (the clock), and the tet then: the slot may
  // hold another tet since.
  struct TetFailure
  {
    std::uint64_t clock = 0;
    TetVertices verts{};
  };
  using TetMemo = EpochHashTable<std::uint64_t, TetFailure, MixHash64>;
  // What one piece of a pass works with: the whole mesh on this thread, or one half of space
  // on a thread of its own (passInHalves). The Optimizer's per-vertex memo arrays are
  // shared: a half reads and writes only the entries of its own vertices, and its clock
  // starts from the whole's and gives it back, so that every stamp stays comparable. The
  // edge and tet memos are per half (the first half's are the whole's).
  struct Worker
  {
    Context* ctx = nullptr;
    EdgeMemo* edgeFailed = nullptr;
    TetMemo* tetFailed = nullptr;
    std::vector<TetId> tetFailedWrites; // the tets this worker wrote to its tet memo
    std::uint64_t clock = 1;
    std::vector<TetId> star;
    TetSlotPool* pool = nullptr;  // a half's tet slots; null: the mesh's free list
    bool reportsProgress = false; // polls the caller's progress (its thread only)
    OptimizationResult moves;     // counters of the moves made
    int changes = 0;
    std::int64_t moveCount = 0, moveBudget = -1; // smoothing moves this pass, and their bound
    std::vector<TetId> postponedTets;            // a half's: work that needs the other side
    std::vector<TetId> insertionTets;            // a half's: stuck tets left for insertion
    std::vector<VertexId> postponedVertices;
  };

  // minDihCosine: the least TetEval::dihCosine (dihedralDegrees gives the smallest angle).
  // unscaledQ: when given, also measureTetQuality of every live tet, in slot order (the
  // tets are measured, and cached, whether the cache held them or not).
  void summarize(double& minQ,
    double& meanQ,
    double& minDihCosine,
    double& share,
    int& count,
    std::vector<double>* unscaledQ = nullptr) const;
  // summarize into r's "before" or "after" statistics, the smallest angle in degrees.
  void summarizeBefore(OptimizationResult& r) const
  {
    summarize(r.minQualityBefore,
      r.meanBefore,
      r.minDihedralBefore,
      r.shareBelowTargetBefore,
      r.tetsBefore,
      ctx_.options.recordQualityBefore ? &r.qualityBefore : nullptr);
    r.minDihedralBefore = dihedralDegrees(r.minDihedralBefore);
  }
  void summarizeAfter(OptimizationResult& r) const
  {
    summarize(
      r.minQualityAfter, r.meanAfter, r.minDihedralAfter, r.shareBelowTargetAfter, r.tetsAfter);
    r.minDihedralAfter = dihedralDegrees(r.minDihedralAfter);
  }
  // The bad tets (worst first, ties by id: deterministic); with setFloors, also the pass's
  // floors, the mesh's minima now (as summarize gives them). One scan of every tet for both.
  void collectBad(BadList& bad, bool setFloors);
  // body(k, first, last) over the tet slots in two halves, side by side on large meshes: the
  // split depends on the mesh alone, so what the halves gather is the same on one thread or
  // two. Every slot measured (summarizeBefore) was 0.08 s of fandisk at h = 0.0103.
  template<typename Body>
  void scanInHalves(const Body& body) const;
  static constexpr TetId kMinTetsForScanHalves = 65536;
  // False, and nothing changed, when w's pool lacks the slots.
  bool apply(Worker& w, const LocalMove& mv, std::vector<TetId>& created);
  bool improveTet(Worker& w, TetId t, std::vector<TetId>& created);
  // Vertex insertion at tet t (VertexInsertion.h), memoised like the other searches; on the
  // whole's worker only.
  bool insertVertex(Worker& w, TetId t, std::vector<TetId>& created);
  // Whether insertion may still search: its bounds are insertionBudget_ vertices and
  // kInsertionSearchesPerVertex searches per vertex of it. Once they are spent, the halves
  // leave no stuck tet for it (gear.vtp: 6.4k tets a pass, a sixth of its optimisation).
  bool insertionLeft() const
  {
    return res_.insertedVertices + main_.moves.insertedVertices < insertionBudget_ &&
      insertionSearches_ < kInsertionSearchesPerVertex * insertionBudget_;
  }
  // Smoothing through the memo below: false without trying when v's ball is unchanged
  // since v last failed to move.
  bool smooth(Worker& w, VertexId v);
  // Smooths each vertex of `vertices` not seen yet, in order.
  void sweep(Worker& w, const std::vector<VertexId>& vertices, std::vector<char>& seen);
  // Works on `tets` in order, and on the bad tets its moves create (topological moves, then
  // smoothing), each tet at most once in the queue at a time.
  void workQueue(Worker& w, const std::vector<TetId>& tets);
  // One pass's sweep (when `swept`) and queue in two halves of space, side by side, then
  // what needed both halves, in one sequence. bad: the pass's bad tets, worst first.
  void passInHalves(BadList& bad, bool swept);
  bool stopRequested(Worker& w);
  // Marks the vertices of tet t (or of every tet of `tets`) as changed now.
  void touch(Worker& w, TetId t);
  void touch(Worker& w, const std::vector<TetId>& tets)
  {
    for (TetId t : tets)
      touch(w, t);
  }
  // Whether the search at t failed before, on these vertices, none of them changed since.
  bool failedBefore(const TetMemo& memo, TetId t, const TetVertices& tv) const
  {
    const TetFailure* f = memo.find(static_cast<std::uint64_t>(t));
    return f && f->verts == tv && unchangedSince(tv[0], f->clock) &&
      unchangedSince(tv[1], f->clock) && unchangedSince(tv[2], f->clock) &&
      unchangedSince(tv[3], f->clock);
  }
  bool unchangedSince(VertexId v, std::uint64_t stamp) const
  {
    const std::size_t i = static_cast<std::size_t>(v);
    return i < changed_.size() && changed_[i] <= stamp;
  }
  // Every per-vertex and per-tet array a half may index, sized to the mesh now (the halves
  // must not grow shared arrays).
  void sizeForHalves();

  Context ctx_;
  Worker main_;
  const std::function<bool(double)>* progress_ = nullptr;
  bool stop_ = false; // set on the caller's thread only (stopRequested)
  std::size_t pollCounter_ = 0;
  int currentPass_ = 0;
  OptimizationResult res_;
  bool insertionPass_ = false; // the previous pass changed nothing: try insertion
  bool summaryBefore_ = true, summaryAfter_ = true; // see skipSummaries
  int insertionBudget_ = 0; // options.maxInsertedVertices, resolved in run()
  // Searches for an insertion, successful or not. Most fail, and a search costs 20-30
  // topological searches (torus at h/2: 650 searches for 93 insertions, a third of the
  // optimisation time), so they are bounded too: kInsertionSearchesPerVertex per vertex of
  // the budget. 1 rather than 10: the same or higher minimum angles on the sized benchmark's
  // good surfaces (2026-11-28, with the forward-difference smoothing), for a fraction of the
  // insertion time (3 -> 1: optimisation on cube at h/2 0.096 -> 0.090 s, 19% of it was
  // insertion).
  int insertionSearches_ = 0;
  static constexpr int kInsertionSearchesPerVertex = 1;
  // Memo of failures (a failed search is not repeated on an unchanged neighbourhood; the
  // floors only rise, so it would fail again): changed_[v] is the clock of the last change
  // of a tet incident to v, smoothFailed_[v] when smoothing v last failed, tetFailed_ when
  // no topological move was found for a tet, insertFailed_ no vertex insertion. Hash tables:
  // few tets are ever searched (fandisk at h = 0.0103: arrays over every tet slot were 56 MB,
  // the optimiser's peak). The second half of space works on a copy of the tet memo, and
  // what it wrote goes back to the whole's: as one memo, so that the work, which the work
  // bound counts, is the same.
  std::vector<std::uint64_t> changed_, smoothFailed_;
  TetMemo tetFailed_, insertFailed_;
  // The clock when the removal of an edge (edgeKey) last failed. The removal depends only
  // on the edge's shell, which every tet of the edge shares: without the memo an edge was
  // searched once per bad tet around it (gear.vtp at h = 0.127: 87% of the tets are bad).
  // Any change to the shell (a tet of p and q replaced, a ring vertex moved) touches p and q.
  // The second half of space keeps its own (a memo only saves work: one missed repeats a
  // search that fails again).
  EdgeMemo edgeFailed_, edgeFailedSecondHalf_;
  std::vector<char> queued_; // per tet slot: in this pass's queue
  // Per tet slot: a half found no move for it and left it for vertex insertion, which only
  // the sequence after the halves does (passInHalves). Cleared when the slot's tet changes.
  std::vector<char> insertionOnly_;
  // Smoothing moves in this pass, per vertex (see Worker for the total).
  std::vector<int> passMoves_;
  std::int64_t passMoveBudget_ = -1;    // the bound on a pass's smoothing moves (-1: none)
  std::vector<std::int8_t> vertexSide_; // passInHalves: each vertex's half
};

void Optimizer::touch(Worker& w, TetId t)
{
  for (int i = 0; i < 4; ++i)
  {
    const std::size_t v = static_cast<std::size_t>(ctx_.mesh.vertex(t, i));
    if (v >= changed_.size())
    {
      changed_.resize(v + 1, 1);
      smoothFailed_.resize(v + 1, 0);
    }
    changed_[v] = w.clock;
  }
}

bool Optimizer::smooth(Worker& w, VertexId v)
{
  const std::size_t i = static_cast<std::size_t>(v);
  if (i < smoothFailed_.size() && smoothFailed_[i] >= changed_[i])
    return false;
  const int perVertex = ctx_.options.maxSmoothingMovesPerVertex;
  if (i >= passMoves_.size())
    passMoves_.resize(i + 1, 0);
  if ((perVertex > 0 && passMoves_[i] >= perVertex) ||
    (w.moveBudget >= 0 && w.moveCount >= w.moveBudget))
    return false;
  ++w.clock;
  Context& ctx = *w.ctx;
  const bool restrictedBefore = ctx.restricted;
  ctx.restricted = false;
  const bool moved = smoothVertex(ctx, v, w.star);
  const bool restricted = ctx.restricted;
  ctx.restricted = restrictedBefore || restricted;
  if (moved)
  {
    ++passMoves_[i];
    ++w.moveCount;
    touch(w, w.star);
    return true;
  }
  if (restricted)
    return false; // not a failure: the ball is not all this half's
  if (i >= smoothFailed_.size())
  {
    changed_.resize(i + 1, 1);
    smoothFailed_.resize(i + 1, 0);
  }
  smoothFailed_[i] = w.clock;
  return false;
}

template<typename Body>
void Optimizer::scanInHalves(const Body& body) const
{
  ctx_.reserveCache(); // quality() must not grow it while both halves run
  const TetId n = ctx_.mesh.tetCapacity();
  const bool split = n >= kMinTetsForScanHalves;
  const TetId middle = split ? n / 2 : n;
  splitAt(split && wantTwoThreads(0), middle, n, body);
}

void Optimizer::summarize(double& minQ,
  double& meanQ,
  double& minDihCosine,
  double& share,
  int& count,
  std::vector<double>* unscaledQ) const
{
  struct Part
  {
    double minQ = kInf, minDihCosine = kInf, sum = 0;
    int below = 0, count = 0;
    std::vector<double> unscaled;
  } part[2];
  scanInHalves(
    [&](int k, TetId first, TetId last)
    {
      Part& me = part[k];
      if (unscaledQ)
        me.unscaled.reserve(static_cast<std::size_t>(last - first));
      for (TetId t = first; t < last; ++t)
      {
        if (ctx_.mesh.isDeleted(t))
          continue;
        TetEval e;
        if (unscaledQ)
        {
          double plain = 0;
          e = ctx_.evalTet(t, &plain);
          ctx_.store(t, e);
          me.unscaled.push_back(plain);
        }
        else
          e = ctx_.quality(t);
        me.minQ = std::min(me.minQ, e.q);
        me.minDihCosine = std::min(me.minDihCosine, e.dihCosine);
        me.sum += e.q;
        if (e.score < ctx_.options.qualityTarget)
          ++me.below;
        ++me.count;
      }
    });
  if (unscaledQ)
  {
    *unscaledQ = std::move(part[0].unscaled);
    unscaledQ->insert(unscaledQ->end(), part[1].unscaled.begin(), part[1].unscaled.end());
  }
  minQ = std::min(part[0].minQ, part[1].minQ);
  minDihCosine = std::min(part[0].minDihCosine, part[1].minDihCosine);
  const double sum = part[0].sum + part[1].sum;
  const int below = part[0].below + part[1].below;
  count = part[0].count + part[1].count;
  if (count == 0)
  {
    minQ = meanQ = share = 0;
    minDihCosine = -2; // 0 degrees
    return;
  }
  meanQ = sum / count;
  share = static_cast<double>(below) / count;
}

void Optimizer::collectBad(BadList& bad, bool setFloors)
{
  struct Part
  {
    double minQ = kInf, minDihCosine = kInf;
    bool any = false;
    BadList bad;
  } part[2];
  scanInHalves(
    [&](int k, TetId first, TetId last)
    {
      Part& me = part[k];
      for (TetId t = first; t < last; ++t)
        if (!ctx_.mesh.isDeleted(t))
        {
          const TetEval e = ctx_.quality(t);
          me.minQ = std::min(me.minQ, e.q);
          me.minDihCosine = std::min(me.minDihCosine, e.dihCosine);
          me.any = true;
          if (e.score < ctx_.options.qualityTarget)
            me.bad.push_back({ e.score, t });
        }
    });
  bad.swap(part[0].bad);
  bad.insert(bad.end(), part[1].bad.begin(), part[1].bad.end());
  if (setFloors)
  {
    const bool any = part[0].any || part[1].any;
    ctx_.floorQ = any ? std::min(part[0].minQ, part[1].minQ) : 0;
    ctx_.floorDihCosine = any ? std::min(part[0].minDihCosine, part[1].minDihCosine) : -2;
  }
  std::sort(bad.begin(), bad.end()); // (score, id): the same order however it was gathered
}

bool Optimizer::apply(Worker& w, const LocalMove& mv, std::vector<TetId>& created)
{
  if (w.pool && w.pool->available() + mv.oldTets.size() < mv.newTets.size())
  {
    w.ctx->restricted = true; // out of this half's slots: after the halves
    return false;
  }
  std::int32_t region = ctx_.rm.region[static_cast<std::size_t>(mv.oldTets[0])];
  replaceTets(ctx_.mesh, w.ctx->index, mv.oldTets, mv.newTets, &created, w.pool);
  if (ctx_.rm.region.size() < static_cast<std::size_t>(ctx_.mesh.tetCapacity()))
    ctx_.rm.region.resize(static_cast<std::size_t>(ctx_.mesh.tetCapacity()), region);
  ++w.clock;
  for (TetId t : created)
  {
    ctx_.rm.region[static_cast<std::size_t>(t)] = region;
    ctx_.invalidate(t);
    touch(w, t);
  }
  if (mv.kind == 0)
    ++w.moves.flips23;
  else if (mv.kind == 2)
    ++w.moves.multiFaceRemovals;
  else if (mv.kind == 3)
    return true; // vertex insertion, counted by the caller
  else if (mv.oldTets.size() == 3)
    ++w.moves.flips32;
  else
    ++w.moves.edgeRemovals;
  return true;
}

bool Optimizer::insertVertex(Worker& w, TetId t, std::vector<TetId>& created)
{
  if (!insertionLeft())
    return false;
  const TetVertices tv = ctx_.verts(t);
  if (failedBefore(insertFailed_, t, tv))
    return false;
  LocalMove mv;
  ++insertionSearches_;
  const int maxCavity = ctx_.quality(t).score < kFlatScore ? kWideCavity : kCavity;
  if (!findVertexInsertion(ctx_, t, mv, maxCavity))
  {
    insertFailed_.assign(static_cast<std::uint64_t>(t), { w.clock, tv });
    return false;
  }
  ctx_.fixed.resize(static_cast<std::size_t>(ctx_.mesh.vertexCount()), 0);
  apply(w, mv, created);
  ++w.moves.insertedVertices;
  if (ctx_.options.smoothing && smooth(w, ctx_.mesh.vertexCount() - 1))
  {
    ++w.moves.smoothedVertices;
    created = w.star; // the new vertex's ball, whatever it moved
  }
  return true;
}

bool Optimizer::improveTet(Worker& w, TetId t, std::vector<TetId>& created)
{
  Context& ctx = *w.ctx;
  const TetVertices tv = ctx.verts(t);
  if (failedBefore(*w.tetFailed, t, tv))
    return insertionPass_ && insertVertex(w, t, created); // nothing changed since it failed
  LocalMove best, cand;
  bool found = false;
  auto consider = [&](bool ok)
  {
    if (!ok)
      return;
    // The old set always contains t; the per-move rule was checked by the caller.
    if (!found || cand.newMin.score > best.newMin.score)
    {
      best = cand;
      found = true;
    }
  };
  // A search that a half cut short (Context::owns) is not a failure to remember.
  bool restricted = false;
  static const int kEdges[6][2] = { { 0, 1 }, { 0, 2 }, { 0, 3 }, { 1, 2 }, { 1, 3 }, { 2, 3 } };
  for (const auto& e : kEdges)
  {
    const VertexId p = ctx.mesh.vertex(t, e[0]), q = ctx.mesh.vertex(t, e[1]);
    const std::uint64_t key = edgeKey(p, q);
    const std::uint64_t* failed = w.edgeFailed->find(key);
    if (failed && unchangedSince(p, *failed) && unchangedSince(q, *failed))
      continue;
    ctx.restricted = false;
    const bool ok = findEdgeRemoval(ctx, t, p, q, cand);
    if (!ok && !ctx.restricted)
      w.edgeFailed->assign(key, w.clock);
    restricted = restricted || ctx.restricted;
    consider(ok);
  }
  for (int f = 0; f < 4; ++f)
  {
    ctx.restricted = false;
    consider(findMultiFaceRemoval(ctx, t, f, cand));
    restricted = restricted || ctx.restricted;
  }
  ctx.restricted = restricted;
  if (!found)
  {
    if (restricted)
      return false;
    w.tetFailed->assign(static_cast<std::uint64_t>(t), { w.clock, tv });
    if (w.tetFailed != &tetFailed_)
      w.tetFailedWrites.push_back(t);
    return insertionPass_ && insertVertex(w, t, created);
  }
  return apply(w, best, created);
}

bool Optimizer::stopRequested(Worker& w)
{
  // The second half neither polls (the caller's progress runs on the caller's thread) nor
  // stops early: a stop that the first half's polls decide (the work bound of the callers,
  // VolumeMeshOptions::optimizationPolls) then gives the same mesh on one thread or two. Its
  // queue's own bound ends it.
  if (!w.reportsProgress)
    return false;
  if (stop_)
    return true;
  if (!*progress_ || (++pollCounter_ & 255u) != 0)
    return false;
  if (!(*progress_)(static_cast<double>(currentPass_) / ctx_.options.passes))
    stop_ = true;
  return stop_;
}

void Optimizer::sweep(Worker& w, const std::vector<VertexId>& vertices, std::vector<char>& seen)
{
  for (VertexId v : vertices)
  {
    if (stopRequested(w))
      break;
    if (seen[static_cast<std::size_t>(v)])
      continue;
    seen[static_cast<std::size_t>(v)] = 1;
    w.ctx->restricted = false;
    if (smooth(w, v))
    {
      ++w.changes;
      ++w.moves.smoothedVertices;
    }
    else if (w.ctx->restricted)
    {
      seen[static_cast<std::size_t>(v)] = 0; // for the sweep after the halves
      w.postponedVertices.push_back(v);
    }
  }
}

void Optimizer::workQueue(Worker& w, const std::vector<TetId>& tets)
{
  Context& ctx = *w.ctx;
  const bool half = ctx.halves();
  std::vector<TetId> created;
  std::deque<TetId> queue;
  auto enqueueIfBad = [&](TetId c)
  {
    const std::size_t i = static_cast<std::size_t>(c);
    if (i >= queued_.size())
      queued_.resize(static_cast<std::size_t>(ctx_.mesh.tetCapacity()), 0);
    if (!queued_[i] && ctx.quality(c).score < ctx.options.qualityTarget)
    {
      queued_[i] = 1;
      queue.push_back(c);
    }
  };
  for (TetId t : tets)
    enqueueIfBad(t);
  std::size_t budget = 20 * queue.size() + 100;
  while (!queue.empty() && budget-- > 0 && !stopRequested(w))
  {
    const TetId t = queue.front();
    queue.pop_front();
    queued_[static_cast<std::size_t>(t)] = 0;
    if (ctx_.mesh.isDeleted(t))
      continue;
    // A half left it for insertion, its searches having failed: with no insertion left,
    // searching again would only repeat the half's work (gear.vtp: the whole pass's 6.4k stuck
    // tets searched again on one thread, for the 16 vertices insertion may add).
    if (!half && static_cast<std::size_t>(t) < insertionOnly_.size() &&
      insertionOnly_[static_cast<std::size_t>(t)])
    {
      insertionOnly_[static_cast<std::size_t>(t)] = 0;
      if (!insertionLeft())
        continue;
    }
    // A tet lifted to the target by a neighbour's move since it was queued is still worked
    // on while a face neighbour is below the target: improving it makes room for that
    // neighbour (skipping every lifted tet cost up to 3 degrees of minimum dihedral angle on
    // Data/, blob-closed 26.4 -> 23.2). With no bad neighbour it is left: on Data/ and the
    // sized cases the minimum angles moved both ways (blob-closed 26.4 -> 28.9, part 1.0 ->
    // 3.3, torus 29.3 -> 28.3, knot1 30.0 -> 28.5) for 10-13% less optimisation time.
    if (!badOrNextToBad(ctx, t))
      continue;
    const TetVertices tv = ctx.verts(t);
    ctx.restricted = false;
    if (!improveTet(w, t, created))
    {
      // No topological move: smooth its free vertices, then requeue the balls' bad tets.
      if (!ctx.options.smoothing)
      {
        if (ctx.restricted)
          w.postponedTets.push_back(t);
        continue;
      }
      bool moved = false;
      created.clear();
      for (VertexId v : tv)
        if (!ctx.fixed[static_cast<std::size_t>(v)] && smooth(w, v))
        {
          moved = true;
          ++w.moves.smoothedVertices;
          created.insert(created.end(), w.star.begin(), w.star.end());
        }
      // Still stuck: vertex insertion right away when enabled (Klingner-Shewchuk), for a
      // tet still below the target only. Insertion is the dearest move and has a bounded
      // budget; tets that neighbours' moves lifted to the target after they were queued
      // are most of what the dihedral stage works on (1362 of 2354 on cube at h/2), and
      // the budget went to them. On the sized benchmark's cases: the same or higher
      // minimum angles, 10-25% less optimisation time on cube and torus at h/2.
      const bool below = ctx.quality(t).score < ctx.options.qualityTarget;
      // (A half reads the insertion bounds; only the sequence after the halves inserts.)
      const bool tryInsertion =
        ctx.options.insertion && !insertionPass_ && below && insertionLeft();
      // A half leaves to the sequence after it what needed the other half, and insertion.
      if (half && ctx.restricted)
        w.postponedTets.push_back(t);
      else if (half && !moved && tryInsertion)
        w.insertionTets.push_back(t);
      if (!moved && (half || !(tryInsertion && insertVertex(w, t, created))))
        continue;
    }
    ++w.changes;
    for (TetId c : created)
    {
      if (!half && static_cast<std::size_t>(c) < insertionOnly_.size())
        insertionOnly_[static_cast<std::size_t>(c)] = 0;
      enqueueIfBad(c);
    }
  }
}

void Optimizer::sizeForHalves()
{
  const std::size_t nv = static_cast<std::size_t>(ctx_.mesh.vertexCount());
  const std::size_t nt = static_cast<std::size_t>(ctx_.mesh.tetCapacity());
  ctx_.reserveCache(); // every live tet is measured (collectBad)
  if (ctx_.rm.region.size() < nt)
    ctx_.rm.region.resize(nt, 0);
  queued_.resize(nt, 0);
  if (changed_.size() < nv)
  {
    changed_.resize(nv, 1);
    smoothFailed_.resize(nv, 0);
  }
  passMoves_.resize(std::max(passMoves_.size(), nv), 0);
}

void Optimizer::passInHalves(BadList& bad, bool swept)
{
  TetMesh& mesh = ctx_.mesh;
  const std::size_t nv = static_cast<std::size_t>(mesh.vertexCount());
  // The split: the median of the bad tets' centroids along their longest extent. A vertex's
  // side is where it lies now; a half's tets are those with all four vertices on its side.
  std::vector<double> centroids(3 * bad.size());
  for (std::size_t i = 0; i < bad.size(); ++i)
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c)
        centroids[3 * i + c] += 0.25 * mesh.point(mesh.vertex(bad[i].second, k))[c];
  int axis = 0;
  double split = 0;
  medianSplit(
    bad.size(), [&](std::size_t i) { return &centroids[3 * i]; }, axis, split);
  vertexSide_.resize(nv);
  for (std::size_t v = 0; v < nv; ++v)
    vertexSide_[v] = mesh.point(static_cast<VertexId>(v))[axis] < split ? 0 : 1;
  auto ownerOf = [&](TetId t) -> int
  {
    const std::int8_t s = vertexSide_[static_cast<std::size_t>(mesh.vertex(t, 0))];
    for (int i = 1; i < 4; ++i)
      if (vertexSide_[static_cast<std::size_t>(mesh.vertex(t, i))] != s)
        return -1;
    return s;
  };
  // Each half's bad tets, in order, and those with vertices on both sides.
  std::vector<TetId> own[2], both;
  auto partition = [&]()
  {
    own[0].clear();
    own[1].clear();
    both.clear();
    for (const auto& b : bad)
    {
      const int s = ownerOf(b.second);
      (s < 0 ? both : own[s]).push_back(b.second);
    }
  };
  partition();
  sizeForHalves();
  // Every free vertex's index entry current (tetOf rebuilds the index at the first stale
  // one): a half reads its own vertices' entries, and must not rebuild the whole index. Once
  // per pass: smoothing and moves keep the entries current.
  for (std::size_t v = 0; v < nv; ++v)
    if (!ctx_.fixed[v])
      ctx_.index.tetOf(ctx_.mesh, static_cast<VertexId>(v));

  const bool twoThreads = wantTwoThreads(0);
  VertexTetIndex secondIndex;
  TetMemo secondTetFailed; // side 1's copy of tetFailed_
  Worker sides[2];
  // The pass's smoothing moves left (-1: no bound) when a runHalves began. Each half gets a
  // share for its own bad tets, so that what comes after the halves finds at least the share
  // of the bad tets on both sides left (with half each, it found none on helix_tube.vtp).
  // Shares on top of the bound for what the halves postponed made poor surfaces slower
  // (alternator.vtp: optimisation 1.8 -> 2.7 s) for no steady gain in quality.
  std::int64_t budgetLeft = -1;
  auto shareOf = [&](std::size_t count) -> std::int64_t
  {
    return budgetLeft < 0 ? -1
                          : static_cast<std::int64_t>(static_cast<double>(budgetLeft) *
                              static_cast<double>(count) / static_cast<double>(bad.size()));
  };
  auto runHalves = [&](const std::function<void(Worker&, int)>& work)
  {
    // Side 0 uses the whole's index and tet memo (this thread does not meanwhile), side 1
    // copies.
    secondIndex.copyEntries(ctx_.index);
    secondTetFailed = tetFailed_;
    Context view0(ctx_, ctx_.index, vertexSide_, 0), view1(ctx_, secondIndex, vertexSide_, 1);
    Context* views[2] = { &view0, &view1 };
    budgetLeft =
      main_.moveBudget < 0 ? -1 : std::max<std::int64_t>(0, main_.moveBudget - main_.moveCount);
    for (int s = 0; s < 2; ++s)
    {
      Worker& w = sides[s];
      w = Worker();
      w.ctx = views[s];
      w.edgeFailed = s == 0 ? &edgeFailed_ : &edgeFailedSecondHalf_;
      w.tetFailed = s == 0 ? &tetFailed_ : &secondTetFailed;
      w.clock = main_.clock;
      w.reportsProgress = s == 0; // this thread's
      w.moveBudget = shareOf(own[s].size());
    }
    runPair(twoThreads, [&](int s) { work(sides[s], s); });
    // Back to the whole: side 1's index entries, the clock past both, the counters.
    ctx_.index.takeEntries(
      secondIndex, [&](VertexId v) { return vertexSide_[static_cast<std::size_t>(v)] == 1; });
    for (TetId t : sides[1].tetFailedWrites)
      tetFailed_.assign(
        static_cast<std::uint64_t>(t), *secondTetFailed.find(static_cast<std::uint64_t>(t)));
    main_.clock = std::max(sides[0].clock, sides[1].clock) + 1;
    for (const Worker& w : sides)
    {
      main_.changes += w.changes;
      main_.moveCount += w.moveCount;
      main_.moves.flips23 += w.moves.flips23;
      main_.moves.flips32 += w.moves.flips32;
      main_.moves.edgeRemovals += w.moves.edgeRemovals;
      main_.moves.multiFaceRemovals += w.moves.multiFaceRemovals;
      main_.moves.smoothedVertices += w.moves.smoothedVertices;
    }
  };

  if (swept)
  {
    std::vector<char> seen(nv, 0);
    auto verticesOf = [&](const std::vector<TetId>& tets)
    {
      std::vector<VertexId> vs;
      for (TetId t : tets)
        for (int i = 0; i < 4; ++i)
        {
          const VertexId v = mesh.vertex(t, i);
          if (!ctx_.fixed[static_cast<std::size_t>(v)])
            vs.push_back(v);
        }
      return vs;
    };
    runHalves([&](Worker& w, int s) { sweep(w, verticesOf(own[s]), seen); });
    std::vector<VertexId> rest = sides[0].postponedVertices;
    rest.insert(rest.end(), sides[1].postponedVertices.begin(), sides[1].postponedVertices.end());
    const std::vector<VertexId> ofBoth = verticesOf(both);
    rest.insert(rest.end(), ofBoth.begin(), ofBoth.end());
    sweep(main_, rest, seen);
    if (ctx_.options.flips)
    {
      collectBad(bad, false);
      partition();
    }
  }
  if (!ctx_.options.flips || stop_)
    return;

  // Each half's tet slots: half the free list each, topped up with fresh slots at the end of
  // the arrays (moves that need more wait for the sequence after the halves).
  TetSlotPool pools[2];
  const std::size_t freeHalf = mesh.freeTets.size() / 2;
  pools[0].freeTets.assign(mesh.freeTets.begin(), mesh.freeTets.begin() + freeHalf);
  pools[1].freeTets.assign(mesh.freeTets.begin() + freeHalf, mesh.freeTets.end());
  mesh.freeTets.clear();
  TetId end = mesh.tetCapacity();
  for (int s = 0; s < 2; ++s)
  {
    const std::size_t want = 256 + 2 * own[s].size();
    const std::size_t fresh = want > pools[s].freeTets.size() ? want - pools[s].freeTets.size() : 0;
    pools[s].next = end;
    pools[s].end = end + static_cast<TetId>(fresh);
    end = pools[s].end;
  }
  const std::size_t oldCapacity = static_cast<std::size_t>(mesh.tetCapacity());
  mesh.tets.resize(4 * static_cast<std::size_t>(end));
  mesh.neighbors.resize(4 * static_cast<std::size_t>(end));
  mesh.flags.resize(static_cast<std::size_t>(end));
  for (std::size_t t = oldCapacity; t < static_cast<std::size_t>(end); ++t)
    mesh.tets[4 * t] = kDeletedTet;
  sizeForHalves();
  std::fill(queued_.begin(), queued_.end(), 0);

  runHalves(
    [&](Worker& w, int s)
    {
      w.pool = &pools[s];
      workQueue(w, own[s]);
    });
  for (const TetSlotPool& pool : pools)
  {
    mesh.freeTets.insert(mesh.freeTets.end(), pool.freeTets.begin(), pool.freeTets.end());
    for (TetId t = pool.next; t < pool.end; ++t)
      mesh.freeTets.push_back(t);
  }

  // What needed both halves, worst first: the bad tets on both sides, and what the halves
  // left (tets their moves needed the other side for, or insertion).
  BadList rest;
  insertionOnly_.assign(static_cast<std::size_t>(mesh.tetCapacity()), 0);
  for (const Worker& w : sides)
    for (TetId t : w.insertionTets)
      if (!mesh.isDeleted(t))
      {
        insertionOnly_[static_cast<std::size_t>(t)] = 1;
        rest.push_back({ ctx_.quality(t).score, t });
      }
  for (const std::vector<TetId>* list : { &both, &sides[0].postponedTets, &sides[1].postponedTets })
    for (TetId t : *list)
      if (!mesh.isDeleted(t))
      {
        insertionOnly_[static_cast<std::size_t>(t)] = 0; // needs the whole search
        rest.push_back({ ctx_.quality(t).score, t });
      }
  std::sort(rest.begin(), rest.end());
  rest.erase(std::unique(rest.begin(), rest.end()), rest.end());
  std::vector<TetId> restTets;
  for (const auto& r : rest)
    restTets.push_back(r.second);
  std::fill(queued_.begin(), queued_.end(), 0); // what the halves' budgets left queued
  workQueue(main_, restTets);
  insertionOnly_.clear();
}

OptimizationResult Optimizer::run(const std::function<bool(double)>& progress)
{
  auto start = std::chrono::steady_clock::now();
  progress_ = &progress;
  const std::size_t nv = static_cast<std::size_t>(ctx_.mesh.vertexCount());
  if (ctx_.size && ctx_.size->size() < nv)
  {
    res_.ok = false;
    res_.error = "vertexSize has fewer entries than the mesh has vertices";
    return res_;
  }
  if (ctx_.rm.region.size() < static_cast<std::size_t>(ctx_.mesh.tetCapacity()))
    ctx_.rm.region.resize(static_cast<std::size_t>(ctx_.mesh.tetCapacity()), 0);
  if (summaryBefore_)
    summarizeBefore(res_);
  else
    res_.tetsBefore = ctx_.mesh.liveTetCount();
  insertionBudget_ = ctx_.options.maxInsertedVertices >= 0 ? ctx_.options.maxInsertedVertices
                                                           : 10 + res_.tetsBefore / 1000;

  // Vertices that never move: those of constrained faces, and those in no tet.
  ctx_.fixed.assign(nv, 1);
  std::vector<char> used(nv, 0);
  for (TetId t = 0; t < ctx_.mesh.tetCapacity(); ++t)
  {
    if (ctx_.mesh.isDeleted(t))
      continue;
    for (int i = 0; i < 4; ++i)
      used[static_cast<std::size_t>(ctx_.mesh.vertex(t, i))] = 1;
  }
  for (std::size_t v = 0; v < nv; ++v)
    ctx_.fixed[v] = used[v] ? 0 : 1;
  for (TetId t = 0; t < ctx_.mesh.tetCapacity(); ++t)
  {
    if (ctx_.mesh.isDeleted(t))
      continue;
    for (int f = 0; f < 4; ++f)
      if (ctx_.mesh.isConstrained(t, f) || ctx_.mesh.neighbor(t, f) == kNoNeighbor)
        for (int k = 0; k < 3; ++k)
          ctx_.fixed[static_cast<std::size_t>(ctx_.mesh.vertex(t, kFaceVertices[f][k]))] = 1;
  }
  for (VertexId v : ctx_.options.fixedVertices)
    if (v >= 0 && static_cast<std::size_t>(v) < nv)
      ctx_.fixed[static_cast<std::size_t>(v)] = 1;
  ctx_.index.rebuild(ctx_.mesh);
  if (ctx_.options.smoothingMovesPerFreeVertex > 0)
    passMoveBudget_ = std::max<std::int64_t>(kMinSmoothingMoveBudget,
      static_cast<std::int64_t>(ctx_.options.smoothingMovesPerFreeVertex *
        static_cast<double>(std::count(ctx_.fixed.begin(), ctx_.fixed.end(), 0))));
  changed_.assign(nv, 1);
  smoothFailed_.assign(nv, 0);

  // Polled every few hundred moves, not only between passes, so that an abort or a caller's
  // time budget takes effect within a pass (one pass can be long on poor surfaces).
  BadList bad;
  // The floor of the driving measure and the bad tets at the previous pass's start.
  double lastFloor = 0;
  std::size_t lastBadCount = 0;
  for (int pass = 0; pass < ctx_.options.passes && !stop_; ++pass)
  {
    currentPass_ = pass;
    passMoves_.assign(passMoves_.size(), 0);
    main_.moveCount = 0;
    main_.moveBudget = passMoveBudget_;
    main_.changes = 0;
    collectBad(bad, true);
    // Nothing below the target: no move of this pass or of a later one (insertion included)
    // has a tet to start from, so the mesh is final. The stages' last passes found nothing
    // on most runs, each a scan of every tet (0.1-0.2 ms at 12k tets, of a 60 ms run).
    if (bad.empty())
      break;
    // The previous pass changed tets but neither lifted the worst one nor left fewer below
    // the target: the surface's triangles bound the tets there, and the moves only trade one
    // poor tet for another (gear.vtp at h = 0.1274, 87% of its tets below Q 0.3: the Q
    // stage's third pass raised nothing and lowered the mean, for 30 ms of a 0.43 s run). A
    // pass after one that changed nothing is the insertion pass: not skipped.
    const double floorNow =
      ctx_.options.measure == QualityMeasure::PaperQ ? ctx_.floorQ : ctx_.floorDihCosine;
    if (pass > 0 && !insertionPass_ && !(floorNow > lastFloor) && bad.size() >= lastBadCount)
    {
      ++res_.stagesEndedWithoutGain;
      break;
    }
    lastFloor = floorNow;
    lastBadCount = bad.size();
    res_.passesRun = pass + 1;

    // A smoothing sweep over the vertices of the bad tets first, when they are many (a
    // poor mesh: the sweep lifts whole regions at once); when they are few, the worst-first
    // queue below (topological moves, then smoothing) does better, and much faster.
    const bool swept =
      ctx_.options.smoothing && static_cast<double>(bad.size()) > 0.1 * ctx_.mesh.liveTetCount();
    const int minHalves = ctx_.options.halvesMinBadTets;
    if (minHalves > 0 && static_cast<int>(bad.size()) >= minHalves && !insertionPass_)
    {
      passInHalves(bad, swept);
      ++res_.passesInHalves;
    }
    else
    {
      if (swept)
      {
        std::vector<VertexId> vs;
        for (const auto& b : bad)
          for (int i = 0; i < 4; ++i)
          {
            VertexId v = ctx_.mesh.vertex(b.second, i);
            if (!ctx_.fixed[static_cast<std::size_t>(v)])
              vs.push_back(v);
          }
        std::vector<char> seen(static_cast<std::size_t>(ctx_.mesh.vertexCount()), 0);
        sweep(main_, vs, seen);
      }
      if (ctx_.options.flips)
      {
        queued_.assign(static_cast<std::size_t>(ctx_.mesh.tetCapacity()), 0);
        if (swept)
          collectBad(bad, false); // else the list is still the mesh's
        std::vector<TetId> tets;
        tets.reserve(bad.size());
        for (const auto& b : bad)
          tets.push_back(b.second);
        workQueue(main_, tets);
      }
    }

    if (stop_ || (progress && !progress(static_cast<double>(pass + 1) / ctx_.options.passes)))
    {
      stop_ = true;
      res_.ok = false;
      res_.error = "aborted";
      break;
    }
    if (main_.changes == 0)
    {
      // Stalled: vertex insertion gets one pass (Klingner-Shewchuk use it as a last resort).
      if (!ctx_.options.insertion || insertionPass_)
        break;
      insertionPass_ = true;
    }
    else
      insertionPass_ = false;
  }
  res_.flips23 += main_.moves.flips23;
  res_.flips32 += main_.moves.flips32;
  res_.edgeRemovals += main_.moves.edgeRemovals;
  res_.multiFaceRemovals += main_.moves.multiFaceRemovals;
  res_.smoothedVertices += main_.moves.smoothedVertices;
  res_.insertedVertices += main_.moves.insertedVertices;

  if (summaryAfter_ || !res_.ok)
    summarizeAfter(res_);
  res_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return res_;
}

} // namespace

OptimizationResult optimizeMesh(RegionMesh& mesh,
  const OptimizationOptions& options,
  const std::vector<double>* vertexSize,
  const std::function<bool(double)>& progress)
{
  const bool dihedralStage =
    options.dihedralTarget > 0 && options.measure == QualityMeasure::PaperQ;
  std::function<bool(double)> firstProgress = progress;
  if (progress && dihedralStage)
    firstProgress = [&](double x) { return progress(0.5 * x); };
  Optimizer first(mesh, options, vertexSize);
  first.skipSummaries(false, dihedralStage);
  OptimizationResult r = first.run(firstProgress);
  if (!r.ok || !dihedralStage)
    return r;
  // Second stage: driven by the smallest dihedral angle, Q guarded by its minimum.
  OptimizationOptions o2 = options;
  o2.measure = QualityMeasure::MinDihedral;
  o2.recordQualityBefore = false; // the first stage's "before" is the mesh's
  // Worked to a fifth past the target, as the Q stage works to 0.35 for 0.3: the tets it
  // cannot lift that far (on surface triangles) end higher. Torus at h = 0.0638: min
  // dihedral 18.7 deg when worked to 25, 22.1 when worked to 30; fandisk at h x1: 25.0 ->
  // 29.8.
  o2.qualityTarget =
    std::min(1.0, kDihedralWorkMargin * options.dihedralTarget / optimization::kRegularDihedral);
  std::function<bool(double)> secondProgress;
  if (progress)
    secondProgress = [&](double x) { return progress(0.5 + 0.5 * x); };
  Optimizer second(mesh, o2, first.sizes());
  second.skipSummaries(true, true);
  second.continueFrom(first);
  OptimizationResult r2 = second.run(secondProgress);
  r.ok = r2.ok;
  r.error = r2.error;
  r.flips23 += r2.flips23;
  r.flips32 += r2.flips32;
  r.edgeRemovals += r2.edgeRemovals;
  r.multiFaceRemovals += r2.multiFaceRemovals;
  r.smoothedVertices += r2.smoothedVertices;
  r.insertedVertices += r2.insertedVertices;
  r.passesRun += r2.passesRun;
  r.passesInHalves += r2.passesInHalves;
  r.stagesEndedWithoutGain += r2.stagesEndedWithoutGain;
  r.seconds += r2.seconds;
  first.summarizeAfter(r, second);
  return r;
}

} // namespace tetmesher
