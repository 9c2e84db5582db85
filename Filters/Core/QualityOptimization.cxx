#include "QualityOptimization.h"

#include "MeshTopology.h"
#include "Predicates.h"
#include "TetQuality.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>

namespace tetmesher
{
namespace
{

constexpr double kRegularDihedral = 70.52877936550931; // degrees
constexpr double kInf = std::numeric_limits<double>::infinity();

// Quality of one tet: the driving score and the two guarded measures.
struct Eval
{
  double score = 0;
  double q = 0;
  double dih = 0;
};

// Worst values over a set of tets.
struct SetMin
{
  double score = kInf;
  double q = kInf;
  double dih = kInf;
  void add(const Eval& e)
  {
    score = std::min(score, e.score);
    q = std::min(q, e.q);
    dih = std::min(dih, e.dih);
  }
};

struct Move
{
  std::vector<TetId> oldTets;
  std::vector<TetVertices> newTets;
  SetMin newMin;
  int kind = 0; // 0: 2-3 flip, 1: edge removal (ring 3 = 3-2 flip), 2: multi-face removal
};

class Optimizer
{
public:
  Optimizer(RegionMesh& rm, const OptimizationOptions& options, const std::vector<double>* h)
    : rm_(rm)
    , m_(rm.mesh)
    , opt_(options)
    , h_(h)
  {
  }

  OptimizationResult run(const std::function<bool(double)>& progress);

private:
  const double* P(VertexId v) const { return m_.point(v); }

  Eval eval(VertexId a, VertexId b, VertexId c, VertexId d) const
  {
    // TetMesh tets are positive in Shewchuk's sign; measureTet expects VTK's: swap a and b.
    TetShape s;
    if (h_)
    {
      const std::vector<double>& h = *h_;
      double hh[4] = { h[b], h[a], h[c], h[d] };
      s = measureTetScaled(P(b), P(a), P(c), P(d), hh);
    }
    else
      s = measureTet(P(b), P(a), P(c), P(d));
    Eval e;
    e.q = s.signedVolume > 0 ? s.quality : 0;
    e.dih = s.signedVolume > 0 ? s.minDihedral : 0;
    e.score = opt_.measure == QualityMeasure::PaperQ ? e.q : e.dih / kRegularDihedral;
    return e;
  }
  Eval eval(const TetVertices& t) const { return eval(t[0], t[1], t[2], t[3]); }
  Eval evalTet(TetId t) const
  {
    return eval(m_.vertex(t, 0), m_.vertex(t, 1), m_.vertex(t, 2), m_.vertex(t, 3));
  }
  // The acceptance rule: the driving measure of the changed set strictly improves, and
  // neither guarded measure drops below both its old value on the set and the mesh's
  // minimum at the start of the pass (so the mesh minima never decrease).
  bool accept(const SetMin& now, const SetMin& old) const
  {
    return now.score > old.score && now.q >= std::min(old.q, floorQ_) &&
      now.dih >= std::min(old.dih, floorDih_);
  }
  bool positive(VertexId a, VertexId b, VertexId c, VertexId d) const
  {
    return predicates::orient3d(P(a), P(b), P(c), P(d)) > 0;
  }
  TetVertices verts(TetId t) const
  {
    return { m_.vertex(t, 0), m_.vertex(t, 1), m_.vertex(t, 2), m_.vertex(t, 3) };
  }

  void summarize(double& minQ, double& meanQ, double& minDih, double& share, int& count) const;
  bool multiFace(TetId t, int f, Move& out) const;
  bool edgeRemoval(TetId t, VertexId p, VertexId q, Move& out);
  void apply(const Move& mv, std::vector<TetId>& created);
  bool improveTet(TetId t, std::vector<TetId>& created);
  bool smoothVertex(VertexId v);
  SetMin starMin(const std::vector<TetId>& star, bool& valid) const;

  RegionMesh& rm_;
  TetMesh& m_;
  OptimizationOptions opt_;
  const std::vector<double>* h_;
  VertexTetIndex index_;
  std::vector<char> fixed_; // vertex on a constrained face (or in no tet)
  std::vector<TetId> star_;
  OptimizationResult res_;
  double floorQ_ = 0, floorDih_ = 0;
};

void Optimizer::summarize(double& minQ,
  double& meanQ,
  double& minDih,
  double& share,
  int& count) const
{
  minQ = kInf;
  minDih = kInf;
  double sum = 0;
  int below = 0;
  count = 0;
  for (TetId t = 0; t < m_.tetCapacity(); ++t)
  {
    if (m_.isDeleted(t))
      continue;
    Eval e = evalTet(t);
    minQ = std::min(minQ, e.q);
    minDih = std::min(minDih, e.dih);
    sum += e.q;
    if (e.score < opt_.qualityTarget)
      ++below;
    ++count;
  }
  if (count == 0)
  {
    minQ = minDih = meanQ = share = 0;
    return;
  }
  meanQ = sum / count;
  share = static_cast<double>(below) / count;
}

bool Optimizer::multiFace(TetId t, int f, Move& out) const
{
  // Faces sandwiched between apexes a and b, oriented so that orient3d(face, a) > 0 (their
  // normal points toward b), each with its two tets. One face: the 2-3 flip.
  struct Sandwiched
  {
    std::array<VertexId, 3> v;
    TetId ta, tb;
  };
  if (m_.isConstrained(t, f))
    return false;
  FaceRef n0 = m_.neighbor(t, f);
  if (n0 == kNoNeighbor)
    return false;
  const VertexId a = m_.vertex(t, f);
  const VertexId b = m_.vertex(faceTet(n0), faceIndex(n0));
  const int* fv = kFaceVertices[f];
  std::vector<Sandwiched> faces = {
    { { m_.vertex(t, fv[0]), m_.vertex(t, fv[1]), m_.vertex(t, fv[2]) }, t, faceTet(n0) }
  };
  bool found = false;
  std::vector<TetVertices> newTets;
  std::vector<std::pair<std::size_t, int>> edges; // boundary edge: face index, edge index
  for (int iter = 0; iter < opt_.maxMultiFace; ++iter)
  {
    // Boundary edges of the face set (directed edges whose reverse is not in the set).
    edges.clear();
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (int e = 0; e < 3; ++e)
      {
        VertexId u = faces[i].v[e], v = faces[i].v[(e + 1) % 3];
        bool inner = false;
        for (std::size_t j = 0; j < faces.size() && !inner; ++j)
          for (int g = 0; g < 3; ++g)
            if (faces[j].v[g] == v && faces[j].v[(g + 1) % 3] == u)
              inner = true;
        if (!inner)
          edges.push_back({ i, e });
      }
    newTets.clear();
    SetMin newMin;
    bool valid = true;
    std::size_t worst = 0;
    double worstScore = kInf;
    for (std::size_t k = 0; k < edges.size(); ++k)
    {
      const Sandwiched& F = faces[edges[k].first];
      int e = edges[k].second;
      TetVertices nt = { F.v[e], F.v[(e + 1) % 3], b, a };
      double sc = -1;
      if (positive(nt[0], nt[1], nt[2], nt[3]))
      {
        Eval ev = eval(nt);
        newMin.add(ev);
        sc = ev.score;
      }
      else
        valid = false;
      if (sc < worstScore)
      {
        worstScore = sc;
        worst = k;
      }
      newTets.push_back(nt);
    }
    if (valid)
    {
      SetMin oldMin;
      for (const Sandwiched& F : faces)
      {
        oldMin.add(evalTet(F.ta));
        oldMin.add(evalTet(F.tb));
      }
      if (accept(newMin, oldMin) && (!found || newMin.score > out.newMin.score))
      {
        found = true;
        out.oldTets.clear();
        for (const Sandwiched& F : faces)
        {
          out.oldTets.push_back(F.ta);
          out.oldTets.push_back(F.tb);
        }
        out.newTets = newTets;
        out.newMin = newMin;
        out.kind = faces.size() == 1 ? 0 : 2;
      }
    }
    // Grow across the bottleneck edge (u,v) of face (u,v,w): the next sandwiched face is
    // (v,u,z) with tets (u,v,a,z) and (u,v,b,z) beyond the faces (u,v,a) and (u,v,b).
    const Sandwiched F = faces[edges[worst].first];
    const int e = edges[worst].second;
    const VertexId u = F.v[e], v = F.v[(e + 1) % 3], w = F.v[(e + 2) % 3];
    int wa = localIndex(m_, F.ta, w), wb = localIndex(m_, F.tb, w);
    if (m_.isConstrained(F.ta, wa) || m_.isConstrained(F.tb, wb))
      break;
    FaceRef na = m_.neighbor(F.ta, wa), nb = m_.neighbor(F.tb, wb);
    if (na == kNoNeighbor || nb == kNoNeighbor)
      break;
    TetId ta = faceTet(na), tb = faceTet(nb);
    VertexId z = m_.vertex(ta, faceIndex(na));
    if (m_.vertex(tb, faceIndex(nb)) != z)
      break;
    int ia = localIndex(m_, ta, a);
    FaceRef mid = m_.neighbor(ta, ia);
    if (mid == kNoNeighbor || faceTet(mid) != tb || m_.isConstrained(ta, ia))
      break;
    bool seen = false;
    for (const Sandwiched& G : faces)
      seen = seen || G.ta == ta || G.tb == tb;
    if (seen || !positive(v, u, z, a))
      break;
    faces.push_back({ { v, u, z }, ta, tb });
  }
  return found;
}

bool Optimizer::edgeRemoval(TetId t, VertexId p, VertexId q, Move& out)
{
  std::vector<TetId> shell;
  std::vector<VertexId> ring;
  if (!edgeShell(m_, t, p, q, shell, ring))
    return false;
  const int n = static_cast<int>(ring.size());
  if (n < 3 || n > opt_.maxEdgeRing || static_cast<int>(shell.size()) != n)
    return false;
  SetMin oldMin;
  for (TetId s : shell)
  {
    for (int f = 0; f < 4; ++f)
    {
      VertexId opp = m_.vertex(s, f);
      if (opp != p && opp != q && m_.isConstrained(s, f))
        return false; // a face around the edge is a constraint
    }
    oldMin.add(evalTet(s));
  }
  // Triangle (i<j<k) of the ring gives tets (ri,rj,rk,q) and (rj,ri,rk,p).
  const int n2 = n * n;
  std::vector<double> tri(static_cast<std::size_t>(n2 * n), -1);
  auto triScore = [&](int i, int j, int k) -> double&
  { return tri[static_cast<std::size_t>(i * n2 + j * n + k)]; };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
      {
        double s = -1;
        if (positive(ring[i], ring[j], ring[k], q) && positive(ring[j], ring[i], ring[k], p))
          s = std::min(
            eval(ring[i], ring[j], ring[k], q).score, eval(ring[j], ring[i], ring[k], p).score);
        triScore(i, j, k) = s;
      }
  std::vector<double> best(static_cast<std::size_t>(n2), -1);
  std::vector<int> choice(static_cast<std::size_t>(n2), -1);
  for (int i = 0; i + 1 < n; ++i)
    best[static_cast<std::size_t>(i * n + i + 1)] = kInf;
  for (int len = 2; len < n; ++len)
    for (int i = 0; i + len < n; ++i)
    {
      int j = i + len;
      double b = -1;
      int c = -1;
      for (int k = i + 1; k < j; ++k)
      {
        double s = std::min({ triScore(i, k, j),
          best[static_cast<std::size_t>(i * n + k)],
          best[static_cast<std::size_t>(k * n + j)] });
        if (s > b)
        {
          b = s;
          c = k;
        }
      }
      best[static_cast<std::size_t>(i * n + j)] = b;
      choice[static_cast<std::size_t>(i * n + j)] = c;
    }
  if (!(best[static_cast<std::size_t>(n - 1)] > oldMin.score))
    return false;
  out.oldTets = shell;
  out.newTets.clear();
  out.newMin = SetMin();
  out.kind = 1;
  std::vector<std::pair<int, int>> stack = { { 0, n - 1 } };
  while (!stack.empty())
  {
    auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2)
      continue;
    int k = choice[static_cast<std::size_t>(i * n + j)];
    TetVertices up = { ring[i], ring[k], ring[j], q };
    TetVertices down = { ring[k], ring[i], ring[j], p };
    out.newTets.push_back(up);
    out.newTets.push_back(down);
    out.newMin.add(eval(up));
    out.newMin.add(eval(down));
    stack.push_back({ i, k });
    stack.push_back({ k, j });
  }
  return accept(out.newMin, oldMin);
}

void Optimizer::apply(const Move& mv, std::vector<TetId>& created)
{
  std::int32_t region = rm_.region[static_cast<std::size_t>(mv.oldTets[0])];
  replaceTets(m_, index_, mv.oldTets, mv.newTets, &created);
  if (rm_.region.size() < static_cast<std::size_t>(m_.tetCapacity()))
    rm_.region.resize(static_cast<std::size_t>(m_.tetCapacity()), region);
  for (TetId t : created)
    rm_.region[static_cast<std::size_t>(t)] = region;
  if (mv.kind == 0)
    ++res_.flips23;
  else if (mv.kind == 2)
    ++res_.multiFaceRemovals;
  else if (mv.oldTets.size() == 3)
    ++res_.flips32;
  else
    ++res_.edgeRemovals;
}

bool Optimizer::improveTet(TetId t, std::vector<TetId>& created)
{
  Move best, cand;
  bool found = false;
  SetMin oldOne;
  oldOne.add(evalTet(t));
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
  static const int kEdges[6][2] = { { 0, 1 }, { 0, 2 }, { 0, 3 }, { 1, 2 }, { 1, 3 }, { 2, 3 } };
  for (const auto& e : kEdges)
    consider(edgeRemoval(t, m_.vertex(t, e[0]), m_.vertex(t, e[1]), cand));
  for (int f = 0; f < 4; ++f)
  {
    consider(multiFace(t, f, cand));
  }
  if (!found)
    return false;
  apply(best, created);
  return true;
}

SetMin Optimizer::starMin(const std::vector<TetId>& star, bool& valid) const
{
  SetMin s;
  valid = true;
  for (TetId t : star)
  {
    if (!positive(m_.vertex(t, 0), m_.vertex(t, 1), m_.vertex(t, 2), m_.vertex(t, 3)))
    {
      valid = false;
      return s;
    }
    s.add(evalTet(t));
  }
  return s;
}

bool Optimizer::smoothVertex(VertexId v)
{
  if (fixed_[static_cast<std::size_t>(v)])
    return false;
  vertexStar(m_, index_, v, star_);
  if (star_.empty())
    return false;
  double* x = &m_.coords[3 * static_cast<std::size_t>(v)];
  const std::array<double, 3> orig = { x[0], x[1], x[2] };
  bool valid = true;
  const SetMin origMin = starMin(star_, valid);
  if (!valid)
    return false;
  auto setPos = [&](const std::array<double, 3>& y)
  {
    x[0] = y[0];
    x[1] = y[1];
    x[2] = y[2];
  };

  // Candidate barycentres.
  std::array<double, 3> wc = { 0, 0, 0 }, ideal = { 0, 0, 0 };
  double wsum = 0, lsum = 0;
  int lcount = 0;
  for (TetId t : star_)
  {
    int iv = localIndex(m_, t, v);
    const int* fv = kFaceVertices[iv];
    const double* a = P(m_.vertex(t, fv[0]));
    const double* b = P(m_.vertex(t, fv[1]));
    const double* c = P(m_.vertex(t, fv[2]));
    double ab[3], ac[3], nrm[3];
    for (int k = 0; k < 3; ++k)
    {
      ab[k] = b[k] - a[k];
      ac[k] = c[k] - a[k];
    }
    nrm[0] = ab[1] * ac[2] - ab[2] * ac[1];
    nrm[1] = ab[2] * ac[0] - ab[0] * ac[2];
    nrm[2] = ab[0] * ac[1] - ab[1] * ac[0];
    double area2 = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    double la = std::sqrt(ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
    double lc = std::sqrt(ac[0] * ac[0] + ac[1] * ac[1] + ac[2] * ac[2]);
    double bc = 0;
    for (int k = 0; k < 3; ++k)
      bc += (c[k] - b[k]) * (c[k] - b[k]);
    double le = (la + lc + std::sqrt(bc)) / 3;
    lsum += le;
    ++lcount;
    // The face's outward normal (seen from its tet) points away from v: v is on the side
    // opposite nrm. Ideal apex: height sqrt(2/3) * mean edge above the centroid, toward v.
    double vol = 0;
    for (int k = 0; k < 3; ++k)
      vol += (x[k] - a[k]) * nrm[k];
    vol = std::abs(vol) / 6;
    for (int k = 0; k < 3; ++k)
    {
      double centroid = (a[k] + b[k] + c[k]) / 3;
      double unit = area2 > 0 ? -nrm[k] / area2 : 0;
      ideal[k] += centroid + unit * le * std::sqrt(2.0 / 3.0);
      wc[k] += vol * (centroid * 3 + x[k]) / 4;
    }
    wsum += vol;
  }
  const double n = static_cast<double>(star_.size());
  for (int k = 0; k < 3; ++k)
  {
    ideal[k] /= n;
    wc[k] = wsum > 0 ? wc[k] / wsum : orig[k];
  }
  const double lavg = lcount ? lsum / lcount : 0;

  std::array<double, 3> cur = orig;
  SetMin curMin = origMin;
  for (const auto& cand : { wc, ideal })
  {
    setPos(cand);
    SetMin s = starMin(star_, valid);
    if (valid && accept(s, curMin))
    {
      cur = cand;
      curMin = s;
    }
  }
  setPos(cur);

  // Ascent on the worst quality of the ball (Klingner-Shewchuk): the gradients of the
  // tets within a margin of the worst (finite differences) span a direction that raises them
  // all, the point of least norm in their convex hull; then backtracking along it.
  std::vector<std::pair<double, TetId>> ranked;
  std::vector<std::array<double, 3>> grads;
  for (int step = 0; step < opt_.smoothingSteps && lavg > 0; ++step)
  {
    ranked.clear();
    for (TetId t : star_)
      ranked.push_back({ evalTet(t).score, t });
    std::sort(ranked.begin(), ranked.end());
    const double ws = ranked[0].first;
    grads.clear();
    const double eps = 1e-6 * lavg;
    for (const auto& [sc, t] : ranked)
    {
      if (sc > ws + 0.03 || grads.size() >= 8)
        break;
      std::array<double, 3> g;
      for (int k = 0; k < 3; ++k)
      {
        x[k] = cur[k] + eps;
        double sp = evalTet(t).score;
        x[k] = cur[k] - eps;
        double sm = evalTet(t).score;
        x[k] = cur[k];
        g[k] = (sp - sm) / (2 * eps);
      }
      grads.push_back(g);
    }
    auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b)
    { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    // Least-norm point of the gradients' hull (Frank-Wolfe with exact line search).
    std::array<double, 3> grad = grads[0];
    for (int it = 0; it < 64 && grads.size() > 1; ++it)
    {
      std::size_t best = 0;
      double bd = kInf;
      for (std::size_t i = 0; i < grads.size(); ++i)
      {
        double d = dot(grads[i], grad);
        if (d < bd)
        {
          bd = d;
          best = i;
        }
      }
      double gg = dot(grad, grad);
      if (gg - bd <= 1e-12 * gg)
        break;
      std::array<double, 3> diff = {
        grads[best][0] - grad[0], grads[best][1] - grad[1], grads[best][2] - grad[2]
      };
      double dd = dot(diff, diff);
      double tstep = dd > 0 ? std::clamp(-dot(grad, diff) / dd, 0.0, 1.0) : 0.0;
      for (int k = 0; k < 3; ++k)
        grad[k] += tstep * diff[k];
    }
    double gn = std::sqrt(dot(grad, grad));
    if (!(gn > 1e-9 / lavg))
      break;
    bool moved = false;
    std::array<double, 3> bestY = cur;
    SetMin bestMin = curMin;
    for (double len = 0.2 * lavg; len > 1e-4 * lavg; len *= 0.5)
    {
      std::array<double, 3> y;
      for (int k = 0; k < 3; ++k)
        y[k] = cur[k] + len * grad[k] / gn;
      setPos(y);
      SetMin s = starMin(star_, valid);
      if (valid && accept(s, curMin) && (!moved || s.score > bestMin.score))
      {
        bestY = y;
        bestMin = s;
        moved = true;
      }
    }
    cur = bestY;
    curMin = bestMin;
    setPos(cur);
    if (!moved)
      break;
  }

  if (accept(curMin, origMin))
  {
    setPos(cur);
    ++res_.smoothedVertices;
    return true;
  }
  setPos(orig);
  return false;
}

OptimizationResult Optimizer::run(const std::function<bool(double)>& progress)
{
  auto start = std::chrono::steady_clock::now();
  const std::size_t nv = static_cast<std::size_t>(m_.vertexCount());
  if (h_ && h_->size() < nv)
  {
    res_.ok = false;
    res_.error = "vertexSize has fewer entries than the mesh has vertices";
    return res_;
  }
  if (rm_.region.size() < static_cast<std::size_t>(m_.tetCapacity()))
    rm_.region.resize(static_cast<std::size_t>(m_.tetCapacity()), 0);
  summarize(res_.minQualityBefore,
    res_.meanBefore,
    res_.minDihedralBefore,
    res_.shareBelowTargetBefore,
    res_.tetsBefore);

  // Vertices that never move: those of constrained faces, and those in no tet.
  fixed_.assign(nv, 1);
  std::vector<char> used(nv, 0);
  for (TetId t = 0; t < m_.tetCapacity(); ++t)
  {
    if (m_.isDeleted(t))
      continue;
    for (int i = 0; i < 4; ++i)
      used[static_cast<std::size_t>(m_.vertex(t, i))] = 1;
  }
  for (std::size_t v = 0; v < nv; ++v)
    fixed_[v] = used[v] ? 0 : 1;
  for (TetId t = 0; t < m_.tetCapacity(); ++t)
  {
    if (m_.isDeleted(t))
      continue;
    for (int f = 0; f < 4; ++f)
      if (m_.isConstrained(t, f) || m_.neighbor(t, f) == kNoNeighbor)
        for (int k = 0; k < 3; ++k)
          fixed_[static_cast<std::size_t>(m_.vertex(t, kFaceVertices[f][k]))] = 1;
  }
  index_.rebuild(m_);

  std::vector<TetId> created;
  for (int pass = 0; pass < opt_.passes; ++pass)
  {
    res_.passesRun = pass + 1;
    int changes = 0;
    {
      double mean, share;
      int count;
      summarize(floorQ_, mean, floorDih_, share, count);
    }
    // Bad tets, worst first (ties by id: deterministic).
    auto collectBad = [&]()
    {
      std::vector<std::pair<double, TetId>> bad;
      for (TetId t = 0; t < m_.tetCapacity(); ++t)
        if (!m_.isDeleted(t))
        {
          double s = evalTet(t).score;
          if (s < opt_.qualityTarget)
            bad.push_back({ s, t });
        }
      std::sort(bad.begin(), bad.end());
      return bad;
    };

    if (opt_.smoothing)
    {
      std::vector<VertexId> vs;
      for (const auto& b : collectBad())
        for (int i = 0; i < 4; ++i)
        {
          VertexId v = m_.vertex(b.second, i);
          if (!fixed_[static_cast<std::size_t>(v)])
            vs.push_back(v);
        }
      std::vector<char> seen(nv, 0);
      for (VertexId v : vs)
      {
        if (seen[static_cast<std::size_t>(v)])
          continue;
        seen[static_cast<std::size_t>(v)] = 1;
        if (smoothVertex(v))
          ++changes;
      }
    }

    if (opt_.flips)
    {
      std::deque<std::pair<TetId, TetVertices>> queue;
      for (const auto& b : collectBad())
        queue.push_back({ b.second, verts(b.second) });
      std::size_t budget = 20 * queue.size() + 100;
      while (!queue.empty() && budget-- > 0)
      {
        auto [t, tv] = queue.front();
        queue.pop_front();
        if (m_.isDeleted(t) || verts(t) != tv)
          continue; // changed since it was queued
        if (!improveTet(t, created))
          continue;
        ++changes;
        for (TetId c : created)
          if (evalTet(c).score < opt_.qualityTarget)
            queue.push_back({ c, verts(c) });
      }
    }

    if (progress && !progress(static_cast<double>(pass + 1) / opt_.passes))
    {
      res_.ok = false;
      res_.error = "aborted";
      break;
    }
    if (changes == 0)
      break;
  }

  summarize(res_.minQualityAfter,
    res_.meanAfter,
    res_.minDihedralAfter,
    res_.shareBelowTargetAfter,
    res_.tetsAfter);
  res_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return res_;
}

} // namespace

OptimizationResult optimizeMesh(RegionMesh& mesh,
  const OptimizationOptions& options,
  const std::vector<double>* vertexSize,
  const std::function<bool(double)>& progress)
{
  Optimizer optimizer(mesh, options, vertexSize);
  return optimizer.run(progress);
}

} // namespace tetmesher
