#include "VertexSmoothing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace tetmesher
{
namespace optimization
{

WorstOf worstOfStar(const Context& ctx, const std::vector<TetId>& star, bool& valid)
{
  WorstOf s;
  valid = true;
  for (TetId t : star)
  {
    if (!ctx.positive(ctx.mesh.vertex(t, 0),
          ctx.mesh.vertex(t, 1),
          ctx.mesh.vertex(t, 2),
          ctx.mesh.vertex(t, 3)))
    {
      valid = false;
      return s;
    }
    s.add(ctx.evalTet(t));
  }
  return s;
}

namespace
{
// Scratch of one smoothVertex call, reused between calls (no allocation in the hot loop).
struct SmoothingScratch
{
  std::vector<double> score, trialScore; // per star tet: at the current / the trial position
  // The whole measures behind score and trialScore: on success they go to the quality
  // cache, which the optimiser's requeueing of the ball reads next (no second measure).
  std::vector<TetEval> eval, trialEval;
  std::vector<std::size_t> order;                   // star indices, worst current score first
  std::vector<std::pair<double, std::size_t>> keys; // rankStar's scratch
  std::vector<std::array<double, 3>> grads;
};

// The ball's values at the vertex's trial position, folded into `now`; false as soon as one
// tet is not positive (exact) or breaks the acceptance rule against `old` on its own (its
// score not above scoreAbove >= old.score, or a guarded measure below the floor), which for
// scoreAbove = old.score is exactly "valid && ctx.accept(now, old)". Tets are tried worst first, so
// most rejections are decided by the first one or two.
bool tryPosition(const Context& ctx,
  const std::vector<TetId>& star,
  const WorstOf& old,
  SmoothingScratch& sc,
  WorstOf& now,
  double scoreAbove)
{
  const double qFloor = std::min(old.q, ctx.floorQ);
  const double dihFloor = std::min(old.dihCosine, ctx.floorDihCosine);
  auto breaksRule = [&](const TetEval& e)
  { return !(e.score > scoreAbove) || e.q < qFloor || e.dihCosine < dihFloor; };
  now = WorstOf();
  for (std::size_t i : sc.order)
  {
    // The driving measure first, then the other, then the exact sign: most trials fail on
    // the first, and the order of pure tests does not change the answer.
    const TetId t = star[i];
    Context::Staged m(ctx, t);
    if (breaksRule(m.values()))
      return false;
    const TetEval& e = m.complete();
    if (breaksRule(e) ||
      !ctx.positive(
        ctx.mesh.vertex(t, 0), ctx.mesh.vertex(t, 1), ctx.mesh.vertex(t, 2), ctx.mesh.vertex(t, 3)))
      return false;
    sc.trialScore[i] = e.score;
    sc.trialEval[i] = e;
    now.add(e);
  }
  return true;
}

void rankStar(SmoothingScratch& sc)
{
  // Insertion sort of (score, index) keys: stars hold 20-40 tets, and the keys need no
  // indirection through sc.score (std::sort on the indices was 3% of the optimiser). The
  // order is the same: (score, index) is a strict total order.
  sc.keys.resize(sc.order.size());
  for (std::size_t k = 0; k < sc.order.size(); ++k)
    sc.keys[k] = { sc.score[sc.order[k]], sc.order[k] };
  for (std::size_t k = 1; k < sc.keys.size(); ++k)
  {
    const std::pair<double, std::size_t> key = sc.keys[k];
    std::size_t j = k;
    for (; j > 0 && key < sc.keys[j - 1]; --j)
      sc.keys[j] = sc.keys[j - 1];
    sc.keys[j] = key;
  }
  for (std::size_t k = 0; k < sc.keys.size(); ++k)
    sc.order[k] = sc.keys[k].second;
}
} // namespace

bool smoothVertex(Context& ctx, VertexId v, std::vector<TetId>& star)
{
  if (ctx.fixed[static_cast<std::size_t>(v)])
    return false;
  vertexStar(ctx.mesh, ctx.index, v, star);
  if (star.empty())
    return false;
  // In a half, v's whole ball must be its side's: moving v changes every tet of it.
  for (TetId t : star)
    if (!ctx.ownsTet(t))
    {
      ctx.restricted = true;
      return false;
    }
  thread_local SmoothingScratch sc;
  double* x = &ctx.mesh.coords[3 * static_cast<std::size_t>(v)];
  const std::array<double, 3> orig = { x[0], x[1], x[2] };
  // Live tets are positive (the mesh invariant); their values come from the cache.
  WorstOf origMin;
  sc.score.resize(star.size());
  sc.trialScore.resize(star.size());
  sc.eval.resize(star.size());
  sc.trialEval.resize(star.size());
  sc.order.resize(star.size());
  for (std::size_t i = 0; i < star.size(); ++i)
  {
    const TetEval e = ctx.quality(star[i]);
    origMin.add(e);
    sc.score[i] = e.score;
    sc.eval[i] = e;
    sc.order[i] = i;
  }
  rankStar(sc);
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
  for (TetId t : star)
  {
    int iv = localIndex(ctx.mesh, t, v);
    const int* fv = kFaceVertices[iv];
    const double* a = ctx.P(ctx.mesh.vertex(t, fv[0]));
    const double* b = ctx.P(ctx.mesh.vertex(t, fv[1]));
    const double* c = ctx.P(ctx.mesh.vertex(t, fv[2]));
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
  const double n = static_cast<double>(star.size());
  for (int k = 0; k < 3; ++k)
  {
    ideal[k] /= n;
    wc[k] = wsum > 0 ? wc[k] / wsum : orig[k];
  }
  const double lavg = lcount ? lsum / lcount : 0;

  std::array<double, 3> cur = orig;
  WorstOf curMin = origMin;
  WorstOf s;
  for (const auto& cand : { wc, ideal })
  {
    setPos(cand);
    if (tryPosition(ctx, star, curMin, sc, s, curMin.score))
    {
      cur = cand;
      curMin = s;
      sc.score.swap(sc.trialScore);
      sc.eval.swap(sc.trialEval);
      rankStar(sc);
    }
  }
  setPos(cur);

  // Ascent on the worst quality of the ball (Klingner-Shewchuk): the gradients of the
  // tets within a margin of the worst (forward differences) span a direction that raises
  // them all, the point of least norm in their convex hull; then backtracking along it, down
  // to the first acceptable step.
  auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b)
  { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  for (int step = 0; step < ctx.options.smoothingSteps && lavg > 0; ++step)
  {
    const double ws = sc.score[sc.order[0]];
    sc.grads.clear();
    const double eps = 1e-6 * lavg;
    for (std::size_t i : sc.order)
    {
      if (sc.score[i] > ws + 0.03 || sc.grads.size() >= 8)
        break;
      const TetId t = star[i];
      std::array<double, 3> g;
      // Forward differences from the score at cur (sc.score, measured there): one measure
      // per axis instead of two, and eps is far below any step the search takes. Of the
      // measure only the driving part, which alone gives the score.
      for (int k = 0; k < 3; ++k)
      {
        x[k] = cur[k] + eps;
        const double sp = Context::Staged(ctx, t).values().score;
        x[k] = cur[k];
        g[k] = (sp - sc.score[i]) / eps;
      }
      sc.grads.push_back(g);
    }
    // Least-norm point of the gradients' hull (Frank-Wolfe with exact line search).
    std::array<double, 3> grad = sc.grads[0];
    for (int it = 0; it < 64 && sc.grads.size() > 1; ++it)
    {
      std::size_t best = 0;
      double bd = kInf;
      for (std::size_t i = 0; i < sc.grads.size(); ++i)
      {
        double d = dot(sc.grads[i], grad);
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
        sc.grads[best][0] - grad[0], sc.grads[best][1] - grad[1], sc.grads[best][2] - grad[2]
      };
      double dd = dot(diff, diff);
      double tstep = dd > 0 ? std::clamp(-dot(grad, diff) / dd, 0.0, 1.0) : 0.0;
      for (int k = 0; k < 3; ++k)
        grad[k] += tstep * diff[k];
    }
    double gn = std::sqrt(dot(grad, grad));
    if (!(gn > 1e-9 / lavg))
      break;
    // Backtracking from a fifth of the mean edge: the first acceptable step, then shorter
    // ones while they do better still.
    bool moved = false;
    const WorstOf stepStart = curMin;
    const std::array<double, 3> from = cur;
    for (double len = 0.2 * lavg; len > 1e-4 * lavg; len *= 0.5)
    {
      std::array<double, 3> y;
      for (int k = 0; k < 3; ++k)
        y[k] = from[k] + len * grad[k] / gn;
      setPos(y);
      if (tryPosition(ctx, star, stepStart, sc, s, curMin.score))
      {
        cur = y;
        curMin = s;
        sc.score.swap(sc.trialScore);
        sc.eval.swap(sc.trialEval);
        moved = true;
      }
      else if (moved)
        break;
    }
    if (moved)
      rankStar(sc);
    setPos(cur);
    if (!moved)
      break;
  }

  // A gain below kMinSmoothingGain is rounding noise, not worth a move: kept, such moves
  // repeat endlessly on a ball already at its best, each requeuing the ball's bad tets.
  if (ctx.accept(curMin, origMin) && curMin.score >= origMin.score + kMinSmoothingGain)
  {
    setPos(cur);
    for (std::size_t i = 0; i < star.size(); ++i)
      ctx.store(star[i], sc.eval[i]);
    return true;
  }
  setPos(orig);
  return false;
}

} // namespace optimization
} // namespace tetmesher
