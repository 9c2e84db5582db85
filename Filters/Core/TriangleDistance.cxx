#include "TriangleDistance.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace tetmesher
{
namespace geometry
{
namespace
{

double dot(const double* u, const double* v)
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

void sub(const double* u, const double* v, double* out)
{
  for (int k = 0; k < 3; ++k)
    out[k] = u[k] - v[k];
}

double distanceSquared(const double* u, const double* v)
{
  double d[3];
  sub(u, v, d);
  return dot(d, d);
}

} // namespace

double segmentDistanceSquared(const double* p, const double* q, const double* r, const double* s)
{
  // Closest points p + sc (q - p), r + tc (s - r), clamped to the segments (the classic
  // two-parameter minimisation, with the degenerate cases of a point-like segment).
  double d1[3], d2[3], w[3];
  sub(q, p, d1);
  sub(s, r, d2);
  sub(p, r, w);
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, w);
  double sc = 0, tc = 0;
  if (a <= 0 && e <= 0)
    return distanceSquared(p, r);
  if (a <= 0)
    tc = std::clamp(f / e, 0.0, 1.0);
  else
  {
    const double c = dot(d1, w);
    if (e <= 0)
      sc = std::clamp(-c / a, 0.0, 1.0);
    else
    {
      const double b = dot(d1, d2), denom = a * e - b * b;
      sc = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      tc = (b * sc + f) / e;
      if (tc < 0)
      {
        tc = 0;
        sc = std::clamp(-c / a, 0.0, 1.0);
      }
      else if (tc > 1)
      {
        tc = 1;
        sc = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  double x[3], y[3];
  for (int k = 0; k < 3; ++k)
  {
    x[k] = p[k] + sc * d1[k];
    y[k] = r[k] + tc * d2[k];
  }
  return distanceSquared(x, y);
}

// Ericson, Real-Time Collision Detection 5.1.5: the Voronoi region of the closest feature
// from six dot products, without the three segment distances (the refinement asks this for
// every candidate point near the boundary).
void gatherTriangle(const double* points, const std::int32_t* ids, double* corner, double* box)
{
  for (int k = 0; k < 3; ++k)
  {
    const double* x = points + 3 * static_cast<std::size_t>(ids[k]);
    for (int a = 0; a < 3; ++a)
    {
      corner[3 * k + a] = x[a];
      box[a] = k == 0 ? x[a] : std::min(box[a], x[a]);
      box[3 + a] = k == 0 ? x[a] : std::max(box[3 + a], x[a]);
    }
  }
}

double pointTriangleDistanceSquared(const double* x,
  const double* a,
  const double* b,
  const double* c)
{
  double ab[3], ac[3], ax[3];
  sub(b, a, ab);
  sub(c, a, ac);
  sub(x, a, ax);
  auto at = [&](double v, double w)
  {
    double q[3];
    for (int k = 0; k < 3; ++k)
      q[k] = a[k] + v * ab[k] + w * ac[k];
    return distanceSquared(x, q);
  };
  const double d1 = dot(ab, ax), d2 = dot(ac, ax);
  if (d1 <= 0 && d2 <= 0)
    return at(0, 0);
  double bx[3];
  sub(x, b, bx);
  const double d3 = dot(ab, bx), d4 = dot(ac, bx);
  if (d3 >= 0 && d4 <= d3)
    return at(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
    return at(d1 / (d1 - d3), 0);
  double cx[3];
  sub(x, c, cx);
  const double d5 = dot(ab, cx), d6 = dot(ac, cx);
  if (d6 >= 0 && d5 <= d6)
    return at(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
    return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w);
  }
  const double denom = va + vb + vc;
  if (!(denom > 0)) // degenerate triangle: its edges
    return std::min({ segmentDistanceSquared(x, x, a, b),
      segmentDistanceSquared(x, x, b, c),
      segmentDistanceSquared(x, x, c, a) });
  return at(vb / denom, vc / denom);
}

double triangleDistanceSquared(const double* const t[3], const double* const u[3])
{
  double best = pointTriangleDistanceSquared(t[0], u[0], u[1], u[2]);
  for (int i = 0; i < 3; ++i)
  {
    best = std::min(best, pointTriangleDistanceSquared(t[i], u[0], u[1], u[2]));
    best = std::min(best, pointTriangleDistanceSquared(u[i], t[0], t[1], t[2]));
    for (int j = 0; j < 3; ++j)
      best = std::min(best, segmentDistanceSquared(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3]));
  }
  return best;
}

} // namespace geometry
} // namespace tetmesher
