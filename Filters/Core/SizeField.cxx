#include "SizeField.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace tetmesher
{

namespace
{
double distance(const double* a, const double* b)
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// det[b-a; c-a; d-a]
double det3(const double* a, const double* b, const double* c, const double* d)
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double w[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
}
} // namespace

std::vector<double> boundaryEdgeSizes(const double* points,
  std::int32_t pointCount,
  const std::int32_t* triangles,
  std::int32_t triangleCount)
{
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  edges.reserve(3 * static_cast<std::size_t>(std::max(triangleCount, 0)));
  for (std::int32_t t = 0; t < triangleCount; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      std::int32_t a = triangles[3 * t + k], b = triangles[3 * t + (k + 1) % 3];
      if (a == b || a < 0 || b < 0 || a >= pointCount || b >= pointCount)
        continue;
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> sum(static_cast<std::size_t>(std::max(pointCount, 0)), 0.0);
  std::vector<int> count(sum.size(), 0);
  for (const auto& [a, b] : edges)
  {
    const double l =
      distance(points + 3 * static_cast<std::size_t>(a), points + 3 * static_cast<std::size_t>(b));
    sum[a] += l;
    sum[b] += l;
    ++count[a];
    ++count[b];
  }
  for (std::size_t v = 0; v < sum.size(); ++v)
    sum[v] = count[v] ? sum[v] / count[v] : 0.0;
  return sum;
}

bool barycentricCoordinates(const double* p, const double* const corners[4], double b[4])
{
  const double total = det3(corners[0], corners[1], corners[2], corners[3]);
  if (total == 0 || !std::isfinite(total))
    return false;
  // b_i: the volume of the tet with corner i replaced by p, over the whole.
  for (int i = 0; i < 4; ++i)
  {
    const double* c[4] = { corners[0], corners[1], corners[2], corners[3] };
    c[i] = p;
    b[i] = det3(c[0], c[1], c[2], c[3]) / total;
  }
  return true;
}

double interpolateSize(const double* p,
  const double* const corners[4],
  const double h[4],
  double power)
{
  if (h[0] == h[1] && h[0] == h[2] && h[0] == h[3])
    return h[0];
  double b[4];
  return interpolateSizeWithCoordinates(
    barycentricCoordinates(p, corners, b) ? b : nullptr, h, power);
}

double interpolateSizeWithCoordinates(const double* coordinates, const double h[4], double power)
{
  if (h[0] == h[1] && h[0] == h[2] && h[0] == h[3])
    return h[0]; // exactly, whatever the weights' rounding
  double b[4];
  double sum = 0;
  if (coordinates)
    for (int i = 0; i < 4; ++i)
    {
      b[i] = std::max(0.0, coordinates[i]);
      sum += b[i];
    }
  if (!(sum > 0))
  {
    for (double& w : b)
      w = 0.25;
    sum = 1;
  }
  for (double& w : b)
    w /= sum;
  if (power == 0)
  {
    double s = 0;
    for (int i = 0; i < 4; ++i)
      s += b[i] * std::log(h[i]);
    return std::exp(s);
  }
  if (power == 1)
    return b[0] * h[0] + b[1] * h[1] + b[2] * h[2] + b[3] * h[3];
  double s = 0;
  for (int i = 0; i < 4; ++i)
    s += b[i] * std::pow(h[i], power);
  return std::pow(s, 1 / power);
}

double scaleAndClampSize(double h, const SizeFieldOptions& options)
{
  h *= options.scale;
  if (options.minSize > 0)
    h = std::max(h, options.minSize);
  if (options.maxSize > 0)
    h = std::min(h, options.maxSize);
  return h;
}

namespace
{
using GradationEntry = std::pair<double, std::int32_t>;
using GradationHeap =
  std::priority_queue<GradationEntry, std::vector<GradationEntry>, std::greater<GradationEntry>>;

// Dijkstra from every vertex in `heap` at once: a vertex popped with its final (smallest) size
// lowers its neighbours; ties broken by id, so the result does not depend on the heap.
// forNeighbours(v, visit) calls visit(w) for each neighbour w of v and returns false to stop.
// onLowered(w, old size) is called when w's size is first lowered.
template<typename ForNeighbours, typename OnLowered>
bool gradeFromHeap(const double* points,
  std::int32_t pointCount,
  double slope,
  double* h,
  GradationHeap& heap,
  const ForNeighbours& forNeighbours,
  const OnLowered& onLowered)
{
  std::vector<char> lowered(static_cast<std::size_t>(pointCount), 0);
  while (!heap.empty())
  {
    // Plain locals, not a structured binding: a lambda below uses them (C++17 does not let
    // lambdas capture bindings; clang refuses it).
    const double hv = heap.top().first;
    const std::int32_t v = heap.top().second;
    heap.pop();
    if (hv != h[v])
      continue; // stale entry
    const double* pv = points + 3 * static_cast<std::size_t>(v);
    const bool ok = forNeighbours(v,
      [&](std::int32_t w)
      {
        const double bound = hv + slope * distance(pv, points + 3 * static_cast<std::size_t>(w));
        if (bound < h[w])
        {
          if (!lowered[w])
          {
            lowered[w] = 1;
            onLowered(w, h[w]);
          }
          h[w] = bound;
          heap.emplace(bound, w);
        }
      });
    if (!ok)
      return false;
  }
  return true;
}
} // namespace

std::int64_t limitGradation(const double* points,
  std::int32_t pointCount,
  const std::int32_t* offsets,
  const std::int32_t* targets,
  double gradation,
  double* h,
  const std::int32_t* seeds,
  std::int32_t seedCount)
{
  if (!(gradation > 1) || pointCount <= 0)
    return 0;
  // Only the vertices that lower a neighbour start: one that lowers none now would lower one
  // only after its own size fell, and then it is pushed. The same sizes (the largest within
  // the bound on every edge), without a heap of every vertex (fandisk at h = 0.0103: 193k
  // pushes and pops, most of the gradation's time, for a few thousand lowered).
  const double slope = gradation - 1;
  auto lowersOne = [&](std::int32_t v)
  {
    const double* pv = points + 3 * static_cast<std::size_t>(v);
    for (std::int32_t k = offsets[v]; k < offsets[v + 1]; ++k)
    {
      const std::int32_t w = targets[k];
      if (h[v] + slope * distance(pv, points + 3 * static_cast<std::size_t>(w)) < h[w])
        return true;
    }
    return false;
  };
  GradationHeap heap;
  if (seeds)
  {
    for (std::int32_t i = 0; i < seedCount; ++i)
      if (lowersOne(seeds[i]))
        heap.emplace(h[seeds[i]], seeds[i]);
  }
  else
  {
    for (std::int32_t v = 0; v < pointCount; ++v)
      if (lowersOne(v))
        heap.emplace(h[v], v);
  }
  std::int64_t changed = 0;
  gradeFromHeap(
    points,
    pointCount,
    slope,
    h,
    heap,
    [&](std::int32_t v, const auto& visit)
    {
      for (std::int32_t k = offsets[v]; k < offsets[v + 1]; ++k)
        visit(targets[k]);
      return true;
    },
    [&](std::int32_t, double) { ++changed; });
  return changed;
}

std::int64_t limitGradationFrom(const double* points,
  std::int32_t pointCount,
  double gradation,
  double* h,
  const std::vector<std::int32_t>& seeds,
  const std::function<bool(std::int32_t, std::vector<std::int32_t>&)>& neighbours,
  std::vector<std::int32_t>& lowered)
{
  lowered.clear();
  if (!(gradation > 1) || pointCount <= 0)
    return 0;
  const double slope = gradation - 1;
  std::vector<std::pair<std::int32_t, double>> before; // to restore when stopped
  std::vector<std::int32_t> list;
  auto restore = [&]
  {
    for (auto it = before.rbegin(); it != before.rend(); ++it)
      h[it->first] = it->second;
    lowered.clear();
    return std::int64_t{ -1 };
  };
  // Each seed first takes the bound from its neighbours (a lowering like any other: the
  // sizes stay the largest within the bound on every edge, whichever order lowers them).
  std::vector<char> isLowered(static_cast<std::size_t>(pointCount), 0);
  for (std::int32_t v : seeds)
  {
    if (!neighbours(v, list))
      return restore();
    const double* pv = points + 3 * static_cast<std::size_t>(v);
    for (std::int32_t w : list)
    {
      const double bound = h[w] + slope * distance(points + 3 * static_cast<std::size_t>(w), pv);
      if (bound < h[v])
      {
        if (!isLowered[v])
        {
          isLowered[v] = 1;
          lowered.push_back(v);
          before.emplace_back(v, h[v]);
        }
        h[v] = bound;
      }
    }
  }
  GradationHeap heap;
  for (std::int32_t v : seeds)
    heap.emplace(h[v], v);
  const bool done = gradeFromHeap(
    points,
    pointCount,
    slope,
    h,
    heap,
    [&](std::int32_t v, const auto& visit)
    {
      if (!neighbours(v, list))
        return false;
      for (std::int32_t w : list)
        visit(w);
      return true;
    },
    [&](std::int32_t w, double old)
    {
      if (!isLowered[w])
      {
        isLowered[w] = 1;
        lowered.push_back(w);
      }
      before.emplace_back(w, old);
    });
  return done ? static_cast<std::int64_t>(lowered.size()) : restore();
}

} // namespace tetmesher
