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
#include <cstdint>
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
// angle are the same bit for bit (the core is built with -ffp-contract=off; tested).
// In parts: the volume and the face normals, then Q and the angle each on demand, because
// most of the optimiser's measures decide from the driving one alone (a rejected trial, a
// gradient's difference). Each part is its own chain of operations, so computing one
// without the other gives the same bits.
class TetMeasure
{
public:
  // Points in VTK's orientation; h: the sizes at a, b, c, d, or null.
  TetMeasure(const double* a, const double* b, const double* c, const double* d, const double* h)
    : p_{ a, b, c, d }
    , h_(h)
  {
    // The edges from a (b - a, c - a, d - a), and the volume as measureRaw computes it.
    double fromA[3][3], x[3];
    for (int i = 0; i < 3; ++i)
      sub(p_[i + 1], a, fromA[i]);
    cross(fromA[1], fromA[2], x);
    volume_ = dot(fromA[0], x) / 6.0;
    if (!positive())
      return;
    for (int f = 0; f < 4; ++f)
    {
      double u[3], v[3];
      sub(p_[kFaces[f][1]], p_[kFaces[f][0]], u);
      sub(p_[kFaces[f][2]], p_[kFaces[f][0]], v);
      cross(u, v, normal_[f]);
      normalLength_[f] = std::sqrt(dot(normal_[f], normal_[f]));
      areaSum_ += 0.5 * normalLength_[f];
    }
  }
  // Q and the angle are 0 for a tet that is not positive in VTK's orientation.
  bool positive() const { return volume_ > 0; }
  double q() const { return qWith(h_); }
  // Q without the sizes: measureTetQuality's value, bit for bit.
  double unscaledQ() const { return qWith(nullptr); }
  // The cosine of the smallest dihedral angle (TetEval::dihCosine).
  double dihCosine() const
  {
    if (!positive())
      return -2.0;
    double lowCosine = 2.0;
    for (const auto& E : kEdge)
    {
      const double nk = normalLength_[E[2]], nl = normalLength_[E[3]];
      if (!(nk > 0 && nl > 0))
        return -2.0; // degenerate
      lowCosine =
        std::min(lowCosine, std::clamp(dot(normal_[E[2]], normal_[E[3]]) / (nk * nl), -1.0, 1.0));
    }
    return lowCosine;
  }

private:
  double qWith(const double* h) const
  {
    if (!positive())
      return 0.0;
    // With one h at the four vertices (a constant size field) the longest scaled edge is the
    // longest edge over h: 0.5 * (l/h + l/h) is l/h exactly, and sqrt and division by h > 0
    // are monotone, so sqrt(max l^2) / h is the same double as max(0.5 * (l/h + l/h)), for
    // one square root and one division instead of six and twelve.
    const bool uniform = !h || (h[0] == h[1] && h[0] == h[2] && h[0] == h[3]);
    double longest = 0.0, longestSquared = 0.0;
    for (const auto& E : kEdge)
    {
      double u[3];
      sub(p_[E[0]], p_[E[1]], u);
      if (uniform)
        longestSquared = std::max(longestSquared, dot(u, u));
      else
      {
        const double l = std::sqrt(dot(u, u));
        longest = std::max(longest, 0.5 * (l / h[E[0]] + l / h[E[1]]));
      }
    }
    if (uniform)
      longest = h ? std::sqrt(longestSquared) / h[0] : std::sqrt(longestSquared);
    double inradius = areaSum_ > 0 ? 3.0 * volume_ / areaSum_ : 0.0;
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
    return longest > 0 ? std::min(1.0, kQualityScale * inradius / longest) : 0.0;
  }
  static void sub(const double* u, const double* v, double* r)
  {
    r[0] = u[0] - v[0];
    r[1] = u[1] - v[1];
    r[2] = u[2] - v[2];
  }
  static void cross(const double* u, const double* v, double* r)
  {
    r[0] = u[1] * v[2] - u[2] * v[1];
    r[1] = u[2] * v[0] - u[0] * v[2];
    r[2] = u[0] * v[1] - u[1] * v[0];
  }
  static double dot(const double* u, const double* v)
  {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  }
  static constexpr int kFaces[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 }, { 0, 2, 1 } };
  // Edge (i,j) and the faces k < l opposite the other two vertices, as measureRaw orders them.
  static constexpr int kEdge[6][4] = { { 0, 1, 2, 3 },
    { 0, 2, 1, 3 },
    { 0, 3, 1, 2 },
    { 1, 2, 0, 3 },
    { 1, 3, 0, 2 },
    { 2, 3, 0, 1 } };

  const double* p_[4];
  const double* h_;
  double volume_;
  double normal_[4][3], normalLength_[4];
  double areaSum_ = 0;
};

// The whole measure; score is left 0. unscaledQ, when given, gets the Q without the sizes
// from the same measure.
inline TetEval measureForOptimization(const double* a,
  const double* b,
  const double* c,
  const double* d,
  const double* h,
  double* unscaledQ = nullptr)
{
  const TetMeasure m(a, b, c, d, h);
  TetEval e;
  e.q = m.q();
  e.dihCosine = m.dihCosine();
  if (unscaledQ)
    *unscaledQ = m.unscaledQ();
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
    , index(ownIndex_)
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
  // A view of `main` for one half of space, worked on by a thread of its own while another
  // works on the other half (QualityOptimization.cxx): the same mesh, sizes, options, floors
  // and quality cache; `sideIndex` as its vertex index; and its moves restricted to the
  // tets whose four vertices are on `side` of `vertexSide` (see owns).
  Context(Context& main,
    VertexTetIndex& sideIndex,
    const std::vector<std::int8_t>& vertexSide,
    std::int8_t side)
    : rm(main.rm)
    , mesh(main.mesh)
    , options(main.options)
    , size(main.size)
    , index(sideIndex)
    , fixed(main.fixed)
    , floorQ(main.floorQ)
    , floorDihCosine(main.floorDihCosine)
    , vertexSide_(&vertexSide)
    , side_(side)
    , cache_(main.cache_)
  {
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Ownership in a half of space. Such a view changes only tets whose four vertices are its
  // side's (its own), reads tets that have one of its vertices (they are its own, or have
  // vertices on both sides, and then no side changes them), and never reads the other
  // side's: the operations check owns() before they step across a face that is not wholly
  // their side's, and set `restricted` when a move would need another side's vertex, so that
  // the tet is worked on again after the halves, by one thread. Always true outside halves.
  bool halves() const { return vertexSide_ != nullptr; }
  bool owns(VertexId v) const
  {
    return !vertexSide_ || (*vertexSide_)[static_cast<std::size_t>(v)] == side_;
  }
  bool ownsTet(TetId t) const
  {
    return owns(mesh.vertex(t, 0)) && owns(mesh.vertex(t, 1)) && owns(mesh.vertex(t, 2)) &&
      owns(mesh.vertex(t, 3));
  }
  // owns(v), else marks this context restricted.
  bool claim(VertexId v) const
  {
    if (owns(v))
      return true;
    restricted = true;
    return false;
  }

  const double* P(VertexId v) const { return mesh.point(v); }

  // unscaledQ, when given: also the Q without the sizes (measureTetQuality's value).
  TetEval eval(VertexId a, VertexId b, VertexId c, VertexId d, double* unscaledQ = nullptr) const
  {
    // TetMesh tets are positive in Shewchuk's sign; the measure expects VTK's: swap a and b.
    double hh[4];
    TetEval e = measureForOptimization(P(b), P(a), P(c), P(d), sizesOf(a, b, c, d, hh), unscaledQ);
    e.score = scoreOf(e);
    return e;
  }
  // eval() in two steps, for callers that reject most tets on the driving measure alone:
  // values() are first the score and the driving measure, the other measure +inf (it passes
  // any floor), and after complete() all of eval()'s.
  class Staged
  {
  public:
    Staged(const Context& ctx, VertexId a, VertexId b, VertexId c, VertexId d)
      : m_(ctx.P(b), ctx.P(a), ctx.P(c), ctx.P(d), ctx.sizesOf(a, b, c, d, hh_))
      , dihedral_(ctx.options.measure != QualityMeasure::PaperQ)
    {
      if (dihedral_)
      {
        e_.dihCosine = m_.dihCosine();
        e_.score = dihedralScore(e_.dihCosine);
        e_.q = kInf;
      }
      else
      {
        e_.q = m_.q();
        e_.score = e_.q;
        e_.dihCosine = kInf;
      }
    }
    Staged(const Context& ctx, TetId t)
      : Staged(ctx,
          ctx.mesh.vertex(t, 0),
          ctx.mesh.vertex(t, 1),
          ctx.mesh.vertex(t, 2),
          ctx.mesh.vertex(t, 3))
    {
    }
    Staged(const Staged&) = delete; // m_ may point into hh_
    Staged& operator=(const Staged&) = delete;
    const TetEval& values() const { return e_; }
    const TetEval& complete()
    {
      if (dihedral_)
        e_.q = m_.q();
      else
        e_.dihCosine = m_.dihCosine();
      return e_;
    }

  private:
    double hh_[4];
    TetMeasure m_;
    bool dihedral_;
    TetEval e_;
  };
  TetEval eval(const TetVertices& t) const { return eval(t[0], t[1], t[2], t[3]); }
  TetEval evalTet(TetId t, double* unscaledQ = nullptr) const
  {
    return eval(
      mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3), unscaledQ);
  }
  // evalTet through a per-slot cache. The optimiser calls invalidate() for every tet it
  // creates and for the ball of every vertex it moves, so an entry is never stale; do not
  // use it for tets whose vertices are being moved tentatively (smoothing's trials).
  TetEval quality(TetId t) const
  {
    const std::size_t i = static_cast<std::size_t>(t);
    if (i >= cache_->valid.size())
      growCache();
    if (!cache_->valid[i])
    {
      cache_->values[i] = evalTet(t);
      cache_->valid[i] = 1;
    }
    return cache_->values[i];
  }
  void invalidateAll() const { std::fill(cache_->valid.begin(), cache_->valid.end(), 0); }
  // Caches e as tet t's measure; e must be what evalTet(t) gives now (e.g. from a trial).
  void store(TetId t, const TetEval& e) const
  {
    const std::size_t i = static_cast<std::size_t>(t);
    if (i >= cache_->valid.size())
      growCache();
    cache_->values[i] = e;
    cache_->valid[i] = 1;
  }
  // Sizes the cache to the mesh's tet slots: two threads that use it (the optimiser's halves)
  // must not grow it.
  void reserveCache() const { growCache(); }
  // Takes over the cache of `other`, a Context on the same mesh and sizes that may drive by
  // another measure (the next stage of optimizeMesh): Q and the angle do not depend on the
  // measure, so only the scores are redone, and the mesh is not measured again.
  void adoptCache(Context& other)
  {
    cache_->values.swap(other.cache_->values);
    cache_->valid.swap(other.cache_->valid);
    other.invalidateAll();
    for (std::size_t i = 0; i < cache_->values.size(); ++i)
      if (cache_->valid[i])
        cache_->values[i].score = scoreOf(cache_->values[i]);
  }
  double scoreOf(const TetEval& e) const
  {
    return options.measure == QualityMeasure::PaperQ ? e.q : dihedralScore(e.dihCosine);
  }
  void invalidate(TetId t) const
  {
    if (static_cast<std::size_t>(t) < cache_->valid.size())
      cache_->valid[static_cast<std::size_t>(t)] = 0;
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
private:
  VertexTetIndex ownIndex_;

public:
  VertexTetIndex& index;   // ownIndex_, or a half's (the side view constructor)
  std::vector<char> fixed; // per vertex: on a constrained face, or in no tet; never moves
  double floorQ = 0, floorDihCosine = -2;
  // Set by an operation of a half that needed another side's vertex (see owns); the caller
  // clears it.
  mutable bool restricted = false;

private:
  struct QualityCache
  {
    std::vector<TetEval> values;
    std::vector<char> valid;
  };
  void growCache() const
  {
    cache_->valid.resize(static_cast<std::size_t>(mesh.tetCapacity()), 0);
    cache_->values.resize(static_cast<std::size_t>(mesh.tetCapacity()));
  }

  // The sizes at a, b, c, d in the measure's order (eval) into hh; null without a size field.
  const double* sizesOf(VertexId a, VertexId b, VertexId c, VertexId d, double* hh) const
  {
    if (!size)
      return nullptr;
    const std::vector<double>& h = *size;
    hh[0] = h[b];
    hh[1] = h[a];
    hh[2] = h[c];
    hh[3] = h[d];
    return hh;
  }

  const std::vector<std::int8_t>* vertexSide_ = nullptr; // a half's view: each vertex's side
  std::int8_t side_ = 0;
  mutable QualityCache ownCache_;
  QualityCache* cache_ = &ownCache_; // a half's view: its main context's
};

} // namespace optimization
} // namespace tetmesher
