#include "PolygonTriangulation.h"

#include "Predicates.h"

#include <cmath>
#include <limits>

namespace tetmesher
{

namespace
{
// 4 sqrt(3) area / (sum of the squared edges): 1 for an equilateral triangle, 0 for a flat one.
double triangleShape(const double* a, const double* b, const double* c)
{
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
    w[k] = c[k] - b[k];
  }
  const double n[3] = {
    u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
  };
  const double twiceArea = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double squares = u[0] * u[0] + u[1] * u[1] + u[2] * u[2] + v[0] * v[0] + v[1] * v[1] +
    v[2] * v[2] + w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  return squares > 0 ? 2 * std::sqrt(3.0) * twiceArea / squares : 0;
}

bool samePoint(const double* a, const double* b)
{
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}
} // namespace

PolygonNormal polygonNormal(const double* points, const std::int64_t* ids, std::int64_t n)
{
  PolygonNormal result;
  double* normal = result.normal;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const double* a = points + 3 * ids[i];
    const double* b = points + 3 * ids[(i + 1) % n];
    normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
    normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
    normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  for (int k = 1; k < 3; ++k)
    if (std::fabs(normal[k]) > std::fabs(normal[result.dominantAxis]))
      result.dominantAxis = k;
  return result;
}

void triangulatePolygon(const double* points,
  std::int64_t pointCount,
  const std::int64_t* ids,
  std::int64_t n,
  std::vector<std::int32_t>& local)
{
  if (n < 3 || n > std::numeric_limits<std::int32_t>::max())
    return;
  if (n > kMaxEarClippedCorners)
  {
    for (std::int64_t k = 1; k + 1 < n; ++k)
      local.insert(
        local.end(), { 0, static_cast<std::int32_t>(k), static_cast<std::int32_t>(k + 1) });
    return;
  }
  const int count = static_cast<int>(n);
  auto corner = [&](int i) { return points + 3 * ids[i]; };
  const std::size_t first = local.size();
  auto fan = [&]()
  {
    local.resize(first);
    for (int k = 1; k + 1 < count; ++k)
      local.insert(local.end(), { 0, k, k + 1 });
  };
  bool idsValid = true;
  for (int i = 0; i < count; ++i)
    idsValid = idsValid && ids[i] >= 0 && ids[i] < pointCount;
  if (count == 3 || !idsValid)
  {
    fan();
    return;
  }
  const PolygonNormal newell = polygonNormal(points, ids, n);
  const double* normal = newell.normal;
  const int drop = newell.dominantAxis;
  if (!(std::fabs(normal[drop]) > 0) || !std::isfinite(normal[drop]))
  {
    fan();
    return;
  }
  // orient2d's sign is that of the dropped component of (b-a)x(c-a): times `side`, positive
  // for a left turn of the polygon's own orientation.
  const int side = normal[drop] > 0 ? 1 : -1;
  auto turn = [&](const double* a, const double* b, const double* c)
  { return side * predicates::orient2d(a, b, c, drop); };

  std::vector<int> prev(static_cast<std::size_t>(count)), next(prev.size());
  for (int i = 0; i < count; ++i)
  {
    prev[static_cast<std::size_t>(i)] = (i + count - 1) % count;
    next[static_cast<std::size_t>(i)] = (i + 1) % count;
  }
  std::vector<char> alive(prev.size(), 1), ear(prev.size(), 0);
  std::vector<double> shape(prev.size(), 0);
  // Orientation tests left: past the bound, the fan (pathological polygons re-classify
  // corners many times).
  std::int64_t work = kEarClippingWork * n * n;
  auto classify = [&](int v)
  {
    const int p = prev[static_cast<std::size_t>(v)], q = next[static_cast<std::size_t>(v)];
    const double* a = corner(p);
    const double* b = corner(v);
    const double* c = corner(q);
    bool isEar = turn(a, b, c) > 0;
    --work;
    for (int w = next[static_cast<std::size_t>(q)]; isEar && w != p;
         w = next[static_cast<std::size_t>(w)])
    {
      work -= 3;
      const double* x = corner(w);
      if (samePoint(x, a) || samePoint(x, b) || samePoint(x, c))
        continue;
      isEar = !(turn(a, b, x) >= 0 && turn(b, c, x) >= 0 && turn(c, a, x) >= 0);
    }
    ear[static_cast<std::size_t>(v)] = isEar;
    shape[static_cast<std::size_t>(v)] = isEar ? triangleShape(a, b, c) : 0;
  };
  for (int v = 0; v < count; ++v)
    classify(v);
  for (int remaining = count; remaining > 3; --remaining)
  {
    int best = -1;
    for (int v = 0; v < count; ++v)
    {
      const auto i = static_cast<std::size_t>(v);
      if (alive[i] && ear[i] && (best < 0 || shape[i] > shape[static_cast<std::size_t>(best)]))
        best = v;
    }
    if (best < 0 || work < 0)
    {
      fan();
      return;
    }
    const int p = prev[static_cast<std::size_t>(best)], q = next[static_cast<std::size_t>(best)];
    local.insert(local.end(), { p, best, q });
    alive[static_cast<std::size_t>(best)] = 0;
    next[static_cast<std::size_t>(p)] = q;
    prev[static_cast<std::size_t>(q)] = p;
    classify(p);
    classify(q);
    // The cut corner no longer blocks the corners whose triangle held it: they may be ears now.
    const double* cut = corner(best);
    for (int w = next[static_cast<std::size_t>(q)]; w != p; w = next[static_cast<std::size_t>(w)])
    {
      const auto i = static_cast<std::size_t>(w);
      if (ear[i])
        continue;
      const double* a = corner(prev[i]);
      const double* b = corner(w);
      const double* c = corner(next[i]);
      work -= 3;
      if (turn(a, b, cut) >= 0 && turn(b, c, cut) >= 0 && turn(c, a, cut) >= 0)
        classify(w);
    }
  }
  int a = 0;
  while (!alive[static_cast<std::size_t>(a)])
    ++a;
  const int b = next[static_cast<std::size_t>(a)];
  local.insert(local.end(), { a, b, next[static_cast<std::size_t>(b)] });
}

} // namespace tetmesher
