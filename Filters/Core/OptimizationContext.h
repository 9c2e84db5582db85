// Shared state of the quality optimiser's local operations (QualityOptimization.h): how a
// tet is measured, the acceptance rule, exact validity, and the locked vertices. Internal to
// the optimiser; one Context per optimizeMesh call.
#pragma once

#include "MeshTopology.h"
#include "Predicates.h"
#include "QualityOptimization.h"
#include "TetQuality.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace tetmesher
{
namespace optimization
{

constexpr double kRegularDihedral = 70.52877936550931; // degrees
constexpr double kInf = std::numeric_limits<double>::infinity();

// Quality of one tet: the driving score (in [0,1]) and the two guarded measures.
struct TetEval
{
  double score = 0;
  double q = 0;   // the paper's Q (size-scaled with a size field)
  double dih = 0; // smallest dihedral angle, degrees
};

// Worst values over a set of tets.
struct WorstOf
{
  double score = kInf;
  double q = kInf;
  double dih = kInf;
  void add(const TetEval& e)
  {
    score = std::min(score, e.score);
    q = std::min(q, e.q);
    dih = std::min(dih, e.dih);
  }
};

// A topological move found but not applied: replace oldTets by newTets (all positive).
struct LocalMove
{
  std::vector<TetId> oldTets;
  std::vector<TetVertices> newTets;
  WorstOf newMin;
  int kind = 0; // 0: 2-3 flip, 1: edge removal (3-2 flip for 3 tets), 2: multi-face, 3: insertion
};

class Context
{
public:
  Context(RegionMesh& regionMesh, const OptimizationOptions& opts, const std::vector<double>* h)
    : rm(regionMesh)
    , mesh(regionMesh.mesh)
    , options(opts)
  {
    if (h)
    {
      sizeCopy = *h;
      size = &sizeCopy;
    }
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const double* P(VertexId v) const { return mesh.point(v); }

  TetEval eval(VertexId a, VertexId b, VertexId c, VertexId d) const
  {
    // TetMesh tets are positive in Shewchuk's sign; measureTet expects VTK's: swap a and b.
    TetShape s;
    if (size)
    {
      const std::vector<double>& h = *size;
      double hh[4] = { h[b], h[a], h[c], h[d] };
      s = measureTetForOptimization(P(b), P(a), P(c), P(d), hh);
    }
    else
      s = measureTetForOptimization(P(b), P(a), P(c), P(d), nullptr);
    TetEval e;
    e.q = s.signedVolume > 0 ? s.quality : 0;
    e.dih = s.signedVolume > 0 ? s.minDihedral : 0;
    e.score = options.measure == QualityMeasure::PaperQ ? e.q : e.dih / kRegularDihedral;
    return e;
  }
  TetEval eval(const TetVertices& t) const { return eval(t[0], t[1], t[2], t[3]); }
  TetEval evalTet(TetId t) const
  {
    return eval(mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3));
  }
  // evalTet through a per-slot cache. The optimiser calls invalidate() for every tet it
  // creates and for the ball of every vertex it moves, so an entry is never stale; do not
  // use it for tets whose vertices are being moved tentatively (smoothing's trials).
  TetEval quality(TetId t) const
  {
    const std::size_t i = static_cast<std::size_t>(t);
    if (i >= cacheValid_.size())
    {
      cacheValid_.resize(static_cast<std::size_t>(mesh.tetCapacity()), 0);
      cache_.resize(static_cast<std::size_t>(mesh.tetCapacity()));
    }
    if (!cacheValid_[i])
    {
      cache_[i] = evalTet(t);
      cacheValid_[i] = 1;
    }
    return cache_[i];
  }
  void invalidateAll() const { std::fill(cacheValid_.begin(), cacheValid_.end(), 0); }
  void invalidate(TetId t) const
  {
    if (static_cast<std::size_t>(t) < cacheValid_.size())
      cacheValid_[static_cast<std::size_t>(t)] = 0;
  }
  // The acceptance rule: the driving measure of the changed set strictly improves, and
  // neither guarded measure drops below both its old value on the set and the mesh's
  // minimum at the start of the pass (floorQ, floorDih), so the mesh minima never decrease.
  bool accept(const WorstOf& now, const WorstOf& old) const
  {
    return now.score > old.score && now.q >= std::min(old.q, floorQ) &&
      now.dih >= std::min(old.dih, floorDih);
  }
  // Exact: orient3d > 0.
  bool positive(VertexId a, VertexId b, VertexId c, VertexId d) const
  {
    return predicates::orient3d(P(a), P(b), P(c), P(d)) > 0;
  }
  // A candidate tet of a move: its score, also folded into `worst`; or -1 when it is not
  // positively oriented, which makes the whole move invalid.
  double scoreCandidate(const TetVertices& t, WorstOf& worst, bool& valid) const
  {
    if (!positive(t[0], t[1], t[2], t[3]))
    {
      valid = false;
      return -1;
    }
    TetEval ev = eval(t);
    worst.add(ev);
    return ev.score;
  }
  TetVertices verts(TetId t) const
  {
    return { mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3) };
  }

  RegionMesh& rm;
  TetMesh& mesh;
  OptimizationOptions options;
  const std::vector<double>* size = nullptr; // &sizeCopy when a size field is given
  std::vector<double> sizeCopy;              // grows with inserted vertices
  VertexTetIndex index;
  std::vector<char> fixed; // per vertex: on a constrained face, or in no tet; never moves
  double floorQ = 0, floorDih = 0;

private:
  mutable std::vector<TetEval> cache_;
  mutable std::vector<char> cacheValid_;
};

} // namespace optimization
} // namespace tetmesher
