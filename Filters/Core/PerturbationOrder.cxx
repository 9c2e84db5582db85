#include "PerturbationOrder.h"

#include "Predicates.h"

#include <cmath>
#include <queue>
#include <utility>

namespace tetmesher
{
namespace
{

struct Quad
{
  VertexId diagonal[2]; // the input edge
  VertexId apex[2];     // the third points of its two triangles
};

VertexId apexOf(const std::array<VertexId, 3>& triangle, VertexId a, VertexId b)
{
  for (VertexId v : triangle)
    if (v != a && v != b)
      return v;
  return -1;
}

// (a,b,c) and (a,b,d) coplanar, c and d on opposite sides of ab, and d on the circumcircle of
// (a,b,c): exact. The circle test takes the sphere through a, b, c and a point x off their
// plane; d, in the plane, is on that sphere exactly when it is on the circle. x need not be
// exact (any point off the plane will do), only checked to be off it.
bool cocircularQuad(const double* a, const double* b, const double* c, const double* d)
{
  if (predicates::orient3d(a, b, c, d) != 0)
    return false;
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double n[3] = {
    u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
  };
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) > std::abs(n[axis]))
      axis = k;
  const int sideC = predicates::orient2d(a, b, c, axis);
  const int sideD = predicates::orient2d(a, b, d, axis);
  if (sideC * sideD >= 0)
    return false;
  const double length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(norm > 0))
    return false;
  const double x[3] = {
    a[0] + n[0] / norm * length, a[1] + n[1] / norm * length, a[2] + n[2] / norm * length
  };
  const int side = predicates::orient3d(a, b, c, x);
  if (side == 0)
    return false;
  // insphere wants (a,b,c,x) positively oriented (orient3d > 0).
  return side > 0 ? predicates::insphere(a, b, c, x, d) == 0
                  : predicates::insphere(b, a, c, x, d) == 0;
}

} // namespace

PerturbationOrder perturbationOrderForSurface(const double* points, const SurfaceInput& surface)
{
  PerturbationOrder order;
  const VertexId n = surface.pointCount;
  auto point = [points](VertexId v) { return points + 3 * static_cast<std::size_t>(v); };
  std::vector<Quad> quads;
  for (std::size_t e = 0; e < surface.edges.size(); ++e)
  {
    const std::int32_t second = surface.edgeSecondTriangle[e];
    if (second < 0)
      continue;
    const VertexId a = surface.edges[e][0], b = surface.edges[e][1];
    const VertexId c = apexOf(surface.triangles[surface.edgeFirstTriangle[e]], a, b);
    const VertexId d = apexOf(surface.triangles[second], a, b);
    if (cocircularQuad(point(a), point(b), point(c), point(d)))
      quads.push_back({ { a, b }, { c, d } });
  }
  order.quads = static_cast<int>(quads.size());
  if (quads.empty())
    return order;

  // The quads of each point (as any of its four vertices), and for each point the number of
  // unresolved quads it is a diagonal end of (it must not be ranked first in those).
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  std::vector<int> blocking(n, 0);
  for (const Quad& q : quads)
  {
    for (VertexId v : { q.diagonal[0], q.diagonal[1], q.apex[0], q.apex[1] })
      ++start[v + 1];
    ++blocking[q.diagonal[0]];
    ++blocking[q.diagonal[1]];
  }
  for (VertexId v = 0; v < n; ++v)
    start[v + 1] += start[v];
  std::vector<int> quadsOf(start[n]);
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < quads.size(); ++i)
      for (VertexId v :
        { quads[i].diagonal[0], quads[i].diagonal[1], quads[i].apex[0], quads[i].apex[1] })
        quadsOf[fill[v]++] = static_cast<int>(i);
  }

  // Free points by id, highest first; blocked ones by (fewest blocking quads, highest id),
  // with stale entries skipped when popped.
  std::priority_queue<VertexId> free;
  std::priority_queue<std::pair<int, VertexId>> blocked;
  for (VertexId v = 0; v < n; ++v)
  {
    if (blocking[v] == 0)
      free.push(v);
    else
      blocked.push({ -blocking[v], v });
  }
  std::vector<char> resolved(quads.size(), 0);
  std::vector<char> ranked(n, 0);
  order.rank.assign(n, 0);
  for (VertexId next = n - 1; next >= 0; --next)
  {
    VertexId v = -1;
    while (!free.empty() && v < 0)
    {
      if (!ranked[free.top()])
        v = free.top();
      free.pop();
    }
    while (v < 0)
    {
      const auto [key, w] = blocked.top();
      blocked.pop();
      if (!ranked[w] && blocking[w] > 0 && -key == blocking[w])
        v = w;
    }
    ranked[v] = 1;
    order.rank[v] = next;
    for (int k = start[v]; k < start[v + 1]; ++k)
    {
      const int i = quadsOf[k];
      if (resolved[i])
        continue;
      resolved[i] = 1;
      const Quad& q = quads[i];
      if (q.apex[0] == v || q.apex[1] == v)
        ++order.satisfied;
      for (VertexId d : q.diagonal)
      {
        if (d == v || ranked[d])
          continue;
        if (--blocking[d] == 0)
          free.push(d);
        else
          blocked.push({ -blocking[d], d });
      }
    }
  }
  return order;
}

} // namespace tetmesher
