#include "EdgeRemoval.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace tetmesher
{
namespace optimization
{

bool findEdgeRemoval(const Context& ctx, TetId t, VertexId p, VertexId q, LocalMove& out)
{
  // Scratch reused between calls (this runs for every edge of every bad tet).
  thread_local std::vector<TetId> shell;
  thread_local std::vector<VertexId> ring;
  thread_local std::vector<WorstOf> tri;
  thread_local std::vector<double> best;
  thread_local std::vector<int> choice;
  thread_local std::vector<std::pair<int, int>> stack;
  thread_local std::vector<std::uint32_t> triStamp;
  thread_local std::uint32_t stamp = 0;
  if (!edgeShell(ctx.mesh, t, p, q, shell, ring))
    return false;
  for (VertexId r : ring)
    if (!ctx.claim(r))
      return false; // a half's move: the shell's tets must be its own
  const int n = static_cast<int>(ring.size());
  if (n < 3 || n > ctx.options.maxEdgeRing || static_cast<int>(shell.size()) != n)
    return false;
  WorstOf oldMin;
  for (TetId s : shell)
  {
    for (int f = 0; f < 4; ++f)
    {
      VertexId opp = ctx.mesh.vertex(s, f);
      if (opp != p && opp != q && ctx.mesh.isConstrained(s, f))
        return false; // a face around the edge is a constraint
    }
    oldMin.add(ctx.quality(s));
  }
  // A tet that breaks the acceptance rule on its own (score not above the shell's worst, or
  // a guarded measure below its floor) rules out every triangulation containing it: such
  // ring triangles are pruned before their second tet is even measured.
  const double qFloor = std::min(oldMin.q, ctx.floorQ);
  const double dihFloor = std::min(oldMin.dihCosine, ctx.floorDihCosine);
  auto usable = [&](const TetEval& e)
  { return e.score > oldMin.score && e.q >= qFloor && e.dihCosine >= dihFloor; };
  // Triangle (i<j<k) of the ring gives tets (ri,rj,rk,q) and (rj,ri,rk,p); tri holds the
  // worst of the two, score -1 when pruned or not positive. Measured on first use (triStamp
  // marks this call's entries, so nothing is cleared between calls).
  const int n2 = n * n;
  const std::size_t cells = static_cast<std::size_t>(n2 * n);
  if (tri.size() < cells)
  {
    tri.resize(cells);
    triStamp.resize(cells, 0);
  }
  if (++stamp == 0)
  {
    std::fill(triStamp.begin(), triStamp.end(), 0);
    stamp = 1;
  }
  auto triAt = [&](int i, int j, int k) -> const WorstOf&
  {
    const std::size_t at = static_cast<std::size_t>(i * n2 + j * n + k);
    WorstOf& w = tri[at];
    if (triStamp[at] == stamp)
      return w;
    triStamp[at] = stamp;
    w.score = -1;
    // Each tet's driving measure, then the other, then the exact signs: most triangles fail
    // on the first, and the order of pure tests does not change the answer.
    Context::Staged up(ctx, ring[i], ring[j], ring[k], q);
    if (!usable(up.values()) || !usable(up.complete()))
      return w;
    Context::Staged down(ctx, ring[j], ring[i], ring[k], p);
    if (!usable(down.values()) || !usable(down.complete()))
      return w;
    if (!ctx.positive(ring[i], ring[j], ring[k], q) || !ctx.positive(ring[j], ring[i], ring[k], p))
      return w;
    w = WorstOf();
    w.add(up.values());
    w.add(down.values());
    return w;
  };
  // Every triangulation of the ring has each ring edge in exactly one triangle, so a ring
  // edge in no usable triangle rules the removal out, and the search below could only find
  // score -1. Most removals fail so (96% of those on gear, ~80% on fandisk and cube), after
  // a few triangles instead of all n(n-1)(n-2)/6.
  for (int e = 0; e < n; ++e)
  {
    const int a = e, b = (e + 1) % n;
    bool covered = false;
    for (int k = 0; k < n && !covered; ++k)
    {
      if (k == a || k == b)
        continue;
      int v[3] = { a, b, k };
      std::sort(v, v + 3);
      covered = triAt(v[0], v[1], v[2]).score >= 0;
    }
    if (!covered)
      return false;
  }
  best.assign(static_cast<std::size_t>(n2), -1);
  choice.assign(static_cast<std::size_t>(n2), -1);
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
        double s = std::min({ triAt(i, k, j).score,
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
  out.newMin = WorstOf();
  out.kind = 1;
  stack.assign(1, { 0, n - 1 });
  while (!stack.empty())
  {
    auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2)
      continue;
    int k = choice[static_cast<std::size_t>(i * n + j)];
    out.newTets.push_back({ ring[i], ring[k], ring[j], q });
    out.newTets.push_back({ ring[k], ring[i], ring[j], p });
    const WorstOf& w = triAt(i, k, j);
    out.newMin.score = std::min(out.newMin.score, w.score);
    out.newMin.q = std::min(out.newMin.q, w.q);
    out.newMin.dihCosine = std::min(out.newMin.dihCosine, w.dihCosine);
    stack.push_back({ i, k });
    stack.push_back({ k, j });
  }
  return ctx.accept(out.newMin, oldMin);
}

} // namespace optimization
} // namespace tetmesher
