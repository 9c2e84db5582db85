#include "EdgeRemoval.h"

#include <algorithm>
#include <cstddef>
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
  if (!edgeShell(ctx.mesh, t, p, q, shell, ring))
    return false;
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
  // worst of the two, score -1 when pruned or not positive.
  const int n2 = n * n;
  // Every entry the search reads (i < j < k) is written first, below: no clearing (this was
  // 32 KB of memset per call for a ring of 10).
  if (tri.size() < static_cast<std::size_t>(n2 * n))
    tri.resize(static_cast<std::size_t>(n2 * n));
  auto triAt = [&](int i, int j, int k) -> WorstOf&
  { return tri[static_cast<std::size_t>(i * n2 + j * n + k)]; };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
      {
        WorstOf& w = triAt(i, j, k);
        w.score = -1;
        if (!ctx.positive(ring[i], ring[j], ring[k], q))
          continue;
        const TetEval up = ctx.eval(ring[i], ring[j], ring[k], q);
        if (!usable(up) || !ctx.positive(ring[j], ring[i], ring[k], p))
          continue;
        const TetEval down = ctx.eval(ring[j], ring[i], ring[k], p);
        if (!usable(down))
          continue;
        w = WorstOf();
        w.add(up);
        w.add(down);
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
