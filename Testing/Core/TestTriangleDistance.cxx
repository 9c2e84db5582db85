// Floating-point distances between points, segments and triangles (TriangleDistance.h), used
// to report how close nearly touching input triangles come.
#include "TriangleDistance.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using tetmesher::geometry::pointTriangleDistanceSquared;
using tetmesher::geometry::segmentDistanceSquared;
using tetmesher::geometry::triangleDistanceSquared;

const double a[3] = { 0, 0, 0 }, b[3] = { 4, 0, 0 }, c[3] = { 0, 4, 0 };

TEST(TriangleDistance, PointAboveTheInteriorIsItsHeight)
{
  const double x[3] = { 1, 1, 3 };
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared(x, a, b, c), 9.0);
  const double y[3] = { 1, 1, 0 }; // in the triangle
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared(y, a, b, c), 0.0);
}

TEST(TriangleDistance, PointBesideIsTheDistanceToTheNearestEdgeOrVertex)
{
  const double x[3] = { 2, -3, 0 }; // below edge ab, in the plane
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared(x, a, b, c), 9.0);
  const double y[3] = { -1, -1, 1 }; // nearest to vertex a
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared(y, a, b, c), 3.0);
  const double z[3] = { 3, 3, 0 }; // beyond the hypotenuse: to (2,2,0)
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared(z, a, b, c), 2.0);
}

TEST(TriangleDistance, DegenerateTriangleIsItsEdges)
{
  const double d[3] = { 2, 0, 0 }; // a, d, b collinear
  const double x[3] = { 2, 5, 0 };
  EXPECT_DOUBLE_EQ(pointTriangleDistanceSquared(x, a, d, b), 25.0);
}

TEST(TriangleDistance, Segments)
{
  const double p[3] = { 0, 0, 0 }, q[3] = { 2, 0, 0 };
  const double r[3] = { 1, -1, 2 }, s[3] = { 1, 1, 2 }; // skew, crossing above at height 2
  EXPECT_DOUBLE_EQ(segmentDistanceSquared(p, q, r, s), 4.0);
  const double u[3] = { 3, 1, 0 }, v[3] = { 5, 1, 0 }; // parallel, beyond q: to (3,1,0)
  EXPECT_DOUBLE_EQ(segmentDistanceSquared(p, q, u, v), 2.0);
  EXPECT_DOUBLE_EQ(segmentDistanceSquared(p, p, u, u), 10.0); // two points
  EXPECT_DOUBLE_EQ(segmentDistanceSquared(u, v, p, q), 2.0);  // symmetric
}

TEST(TriangleDistance, Triangles)
{
  const double* t[3] = { a, b, c };
  // Parallel copy 1e-30 above: the smallest gaps are what the near-touch probe reports.
  const double a2[3] = { 1, 1, 1e-30 }, b2[3] = { 5, 1, 1e-30 }, c2[3] = { 1, 5, 1e-30 };
  const double* u[3] = { a2, b2, c2 };
  EXPECT_DOUBLE_EQ(std::sqrt(triangleDistanceSquared(t, u)), 1e-30);
  // A triangle rising from an edge 1 above the hypotenuse (over (1,3)..(3,1)).
  const double e1[3] = { 3, 1, 1 }, e2[3] = { 1, 3, 1 }, e3[3] = { 4, 4, 5 };
  const double* w[3] = { e1, e2, e3 };
  EXPECT_DOUBLE_EQ(triangleDistanceSquared(t, w), 1.0);
  EXPECT_DOUBLE_EQ(triangleDistanceSquared(w, t), 1.0);
}

} // namespace
