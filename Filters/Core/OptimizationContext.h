// Shared state of the quality optimiser's local operations (QualityOptimization.h): how a
// tet is measured, the acceptance rule, exact validity, and the locked vertices. Internal to
// the optimiser; one Context per optimizeMesh call.
#pragma once

#include "MeshTopology.h"
#include "Predicates.h"
#include "QualityOptimization.h"
#include "TetQuality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tetmesher
{
namespace optimization
{

constexpr double kRegularDihedral = 70.52877936550931; // degrees
constexpr double kInf = std::numeric_limits<double>::infinity();

// The optimiser keeps a tet's smallest dihedral angle as the cosine c between the outward
// normals of the two faces at its sharpest edge (the angle is 180 - acos(c) degrees, which
// grows with c), because the acos was a sixth of the optimiser's time: comparisons need only
// c, and the dihedral stage's score a square root. -2 stands for a degenerate tet (0 degrees),
// 2 for one without a measurable edge (180 degrees).
inline double dihedralDegrees(double cosine)
{
  if (cosine < -1.0)
    return 0.0;
  if (cosine > 1.0)
    return 180.0;
  return 180.0 - std::acos(cosine) * 57.29577951308232;
}
// The dihedral stage's score: sin(angle / 2) = sqrt((1 + c) / 2), over the regular tet's
// (1/sqrt(3)). Monotone in the angle and nearly proportional to it below 70 degrees (within
// 6% of angle / 70.53), so the smoothing's ascent and margins behave as with the angle.
inline double dihedralScore(double cosine)
{
  return std::sqrt(1.5 * std::clamp(1.0 + cosine, 0.0, 2.0));
}
// The score of a tet whose smallest dihedral angle is `degrees`.
inline double dihedralScoreOfDegrees(double degrees)
{
  return dihedralScore(-std::cos(degrees * 0.017453292519943295));
}

// Quality of one tet: the driving score and the two guarded measures.
struct TetEval
{
  double score = 0;
  double q = 0;          // the paper's Q (size-scaled with a size field)
  double dihCosine = -2; // the smallest dihedral angle, as above
};

// Worst values over a set of tets.
struct WorstOf
{
  double score = kInf;
  double q = kInf;
  double dihCosine = kInf;
  void add(const TetEval& e)
  {
    score = std::min(score, e.score);
    q = std::min(q, e.q);
    dihCosine = std::min(dihCosine, e.dihCosine);
  }
};

// measureTetForOptimization (TetQuality.h), inlined and without what the optimiser does not
// use (the largest angle, the search for each edge's two faces): the optimiser's inner loops
// are mostly this. The same arithmetic in the same order, so Q and the smallest dihedral
// angle are the same bit for bit (the core is built with -ffp-contract=off; tested). Q and
// the angle are 0 for a tet that is not positive in VTK's orientation; score is left 0.
inline TetEval measureForOptimization(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* h)
{
  const double* p[4] = { a, b, c, d };
  auto sub = [](const double* u, const double* v, double* r)
  {
    r[0] = u[0] - v[0];
    r[1] = u[1] - v[1];
    r[2] = u[2] - v[2];
  };
  auto cross = [](const double* u, const double* v, double* r)
  {
    r[0] = u[1] * v[2] - u[2] * v[1];
    r[1] = u[2] * v[0] - u[0] * v[2];
    r[2] = u[0] * v[1] - u[1] * v[0];
  };
  auto dot = [](const double* u, const double* v)
  { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  // The edges from a (b - a, c - a, d - a), and the volume as measureRaw computes it.
  double fromA[3][3], x[3];
  for (int i = 0; i < 3; ++i)
    sub(p[i + 1], a, fromA[i]);
  cross(fromA[1], fromA[2], x);
  const double volume = dot(fromA[0], x) / 6.0;
  TetEval e;
  if (!(volume > 0))
    return e;
  static constexpr int kFaces[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 }, { 0, 2, 1 } };
  double normal[4][3], normalLength[4];
  double areaSum = 0;
  for (int f = 0; f < 4; ++f)
  {
    double u[3], v[3];
    sub(p[kFaces[f][1]], p[kFaces[f][0]], u);
    sub(p[kFaces[f][2]], p[kFaces[f][0]], v);
    cross(u, v, normal[f]);
    normalLength[f] = std::sqrt(dot(normal[f], normal[f]));
    areaSum += 0.5 * normalLength[f];
  }
  // Edge (i,j) and the faces k < l opposite the other two vertices, as measureRaw orders them.
  static constexpr int kEdge[6][4] = {
    { 0, 1, 2, 3 }, { 0, 2, 1, 3 }, { 0, 3, 1, 2 }, { 1, 2, 0, 3 }, { 1, 3, 0, 2 }, { 2, 3, 0, 1 }
  };
  // With one h at the four vertices (a constant size field) the longest scaled edge is the
  // longest edge over h: 0.5 * (l/h + l/h) is l/h exactly, and sqrt and division by h > 0
  // are monotone, so sqrt(max l^2) / h is the same double as max(0.5 * (l/h + l/h)), for
  // one square root and one division instead of six and twelve.
  const bool uniform = !h || (h[0] == h[1] && h[0] == h[2] && h[0] == h[3]);
  double lowCosine = 2.0, longest = 0.0, longestSquared = 0.0;
  bool degenerate = false;
  for (const auto& E : kEdge)
  {
    double u[3];
    sub(p[E[0]], p[E[1]], u);
    if (uniform)
      longestSquared = std::max(longestSquared, dot(u, u));
    else
    {
      const double l = std::sqrt(dot(u, u));
      longest = std::max(longest, 0.5 * (l / h[E[0]] + l / h[E[1]]));
    }
    const double nk = normalLength[E[2]], nl = normalLength[E[3]];
    if (nk > 0 && nl > 0)
      lowCosine =
        std::min(lowCosine, std::clamp(dot(normal[E[2]], normal[E[3]]) / (nk * nl), -1.0, 1.0));
    else
      degenerate = true;
  }
  if (uniform)
    longest = h ? std::sqrt(longestSquared) / h[0] : std::sqrt(longestSquared);
  double inradius = areaSum > 0 ? 3.0 * volume / areaSum : 0.0;
  if (h)
  {
    double inverseSum = 0.0;
    if (uniform)
    {
      const double inverse = 1.0 / h[0];
      inverseSum = ((inverse + inverse) + inverse) + inverse;
    }
    else
      for (int i = 0; i < 4; ++i)
        inverseSum += 1.0 / h[i];
    inradius = inradius * inverseSum / 4.0;
  }
  e.dihCosine = degenerate ? -2.0 : lowCosine;
  if (longest > 0)
    e.q = std::min(1.0, kQualityScale * inradius / longest);
  return e;
}

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
    // A target in the public unit of the dihedral measure (angle / 70.53 degrees), as a score.
    if (options.measure == QualityMeasure::MinDihedral)
      options.qualityTarget = dihedralScoreOfDegrees(opts.qualityTarget * kRegularDihedral);
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
    // TetMesh tets are positive in Shewchuk's sign; the measure expects VTK's: swap a and b.
    double hh[4];
    if (size)
    {
      const std::vector<double>& h = *size;
      hh[0] = h[b];
      hh[1] = h[a];
      hh[2] = h[c];
      hh[3] = h[d];
    }
    TetEval e = measureForOptimization(P(b), P(a), P(c), P(d), size ? hh : nullptr);
    e.score = scoreOf(e);
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
  // Caches e as tet t's measure; e must be what evalTet(t) gives now (e.g. from a trial).
  void store(TetId t, const TetEval& e) const
  {
    const std::size_t i = static_cast<std::size_t>(t);
    if (i >= cacheValid_.size())
    {
      cacheValid_.resize(static_cast<std::size_t>(mesh.tetCapacity()), 0);
      cache_.resize(static_cast<std::size_t>(mesh.tetCapacity()));
    }
    cache_[i] = e;
    cacheValid_[i] = 1;
  }
  // Takes over the cache of `other`, a Context on the same mesh and sizes that may drive by
  // another measure (the next stage of optimizeMesh): Q and the angle do not depend on the
  // measure, so only the scores are redone, and the mesh is not measured again.
  void adoptCache(Context& other)
  {
    cache_.swap(other.cache_);
    cacheValid_.swap(other.cacheValid_);
    other.invalidateAll();
    for (std::size_t i = 0; i < cache_.size(); ++i)
      if (cacheValid_[i])
        cache_[i].score = scoreOf(cache_[i]);
  }
  double scoreOf(const TetEval& e) const
  {
    return options.measure == QualityMeasure::PaperQ ? e.q : dihedralScore(e.dihCosine);
  }
  void invalidate(TetId t) const
  {
    if (static_cast<std::size_t>(t) < cacheValid_.size())
      cacheValid_[static_cast<std::size_t>(t)] = 0;
  }
  // The acceptance rule: the driving measure of the changed set strictly improves, and
  // neither guarded measure drops below both its old value on the set and the mesh's
  // minimum at the start of the pass (floorQ, floorDihCosine), so the mesh minima never
  // decrease.
  bool accept(const WorstOf& now, const WorstOf& old) const
  {
    return now.score > old.score && now.q >= std::min(old.q, floorQ) &&
      now.dihCosine >= std::min(old.dihCosine, floorDihCosine);
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
  double floorQ = 0, floorDihCosine = -2;

private:
  mutable std::vector<TetEval> cache_;
  mutable std::vector<char> cacheValid_;
};

} // namespace optimization
} // namespace tetmesher
