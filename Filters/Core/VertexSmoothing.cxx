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

bool smoothVertex(Context& ctx, VertexId v, std::vector<TetId>& star)
{
  if (ctx.fixed[static_cast<std::size_t>(v)])
    return false;
  vertexStar(ctx.mesh, ctx.index, v, star);
  if (star.empty())
    return false;
  double* x = &ctx.mesh.coords[3 * static_cast<std::size_t>(v)];
  const std::array<double, 3> orig = { x[0], x[1], x[2] };
  bool valid = true;
  const WorstOf origMin = worstOfStar(ctx, star, valid);
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
  for (const auto& cand : { wc, ideal })
  {
    setPos(cand);
    WorstOf s = worstOfStar(ctx, star, valid);
    if (valid && ctx.accept(s, curMin))
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
  for (int step = 0; step < ctx.options.smoothingSteps && lavg > 0; ++step)
  {
    ranked.clear();
    for (TetId t : star)
      ranked.push_back({ ctx.evalTet(t).score, t });
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
        double sp = ctx.evalTet(t).score;
        x[k] = cur[k] - eps;
        double sm = ctx.evalTet(t).score;
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
    WorstOf bestMin = curMin;
    for (double len = 0.2 * lavg; len > 1e-4 * lavg; len *= 0.5)
    {
      std::array<double, 3> y;
      for (int k = 0; k < 3; ++k)
        y[k] = cur[k] + len * grad[k] / gn;
      setPos(y);
      WorstOf s = worstOfStar(ctx, star, valid);
      if (valid && ctx.accept(s, curMin) && (!moved || s.score > bestMin.score))
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

  if (ctx.accept(curMin, origMin))
  {
    setPos(cur);
    return true;
  }
  setPos(orig);
  return false;
}

} // namespace optimization
} // namespace tetmesher
