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
  std::vector<TetId> shell;
  std::vector<VertexId> ring;
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
    oldMin.add(ctx.evalTet(s));
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
        if (ctx.positive(ring[i], ring[j], ring[k], q) &&
          ctx.positive(ring[j], ring[i], ring[k], p))
          s = std::min(ctx.eval(ring[i], ring[j], ring[k], q).score,
            ctx.eval(ring[j], ring[i], ring[k], p).score);
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
  out.newMin = WorstOf();
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
    out.newMin.add(ctx.eval(up));
    out.newMin.add(ctx.eval(down));
    stack.push_back({ i, k });
    stack.push_back({ k, j });
  }
  return ctx.accept(out.newMin, oldMin);
}

} // namespace optimization
} // namespace tetmesher
