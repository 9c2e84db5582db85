#include "TriangleDistance.h"

#include <algorithm>
#include <cmath>

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

double pointTriangleDistanceSquared(const double* x,
  const double* a,
  const double* b,
  const double* c)
{
  double ab[3], ac[3], ax[3], n[3];
  sub(b, a, ab);
  sub(c, a, ac);
  sub(x, a, ax);
  n[0] = ab[1] * ac[2] - ab[2] * ac[1];
  n[1] = ab[2] * ac[0] - ab[0] * ac[2];
  n[2] = ab[0] * ac[1] - ab[1] * ac[0];
  const double nn = dot(n, n);
  const double toEdges = std::min({ segmentDistanceSquared(x, x, a, b),
    segmentDistanceSquared(x, x, b, c),
    segmentDistanceSquared(x, x, c, a) });
  if (!(nn > 0))
    return toEdges;
  // Projection of x on the plane; inside the triangle when it is on the inner side of all
  // three edges (signs of the sub-triangle normals along n).
  const double h = dot(ax, n) / nn;
  double y[3];
  for (int k = 0; k < 3; ++k)
    y[k] = x[k] - h * n[k];
  auto side = [&](const double* u, const double* v)
  {
    double uv[3], uy[3], m[3];
    sub(v, u, uv);
    sub(y, u, uy);
    m[0] = uv[1] * uy[2] - uv[2] * uy[1];
    m[1] = uv[2] * uy[0] - uv[0] * uy[2];
    m[2] = uv[0] * uy[1] - uv[1] * uy[0];
    return dot(m, n);
  };
  if (side(a, b) >= 0 && side(b, c) >= 0 && side(c, a) >= 0)
    return std::min(toEdges, h * h * nn);
  return toEdges;
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
