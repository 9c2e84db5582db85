// Size field: boundary edge sizes, the paper's power-mean interpolation, scaling and clamping,
// and the gradation limit; the floor under the sizes next to large boundary faces.
#include "BoundarySizeCeiling.h"
#include "BoundarySizeFloor.h"
#include "SizeField.h"
#include "TriangleDistance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace tetmesher;

TEST(SizeField, BoundaryEdgeSizesAreMeanEdgeLengths)
{
  // Two triangles sharing edge 0-2 of a 2 x 1 rectangle; point 4 is in no triangle.
  const double points[] = { 0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0, 5, 5, 5 };
  const std::int32_t triangles[] = { 0, 1, 2, 0, 2, 3 };
  std::vector<double> h = boundaryEdgeSizes(points, 5, triangles, 2);
  ASSERT_EQ(h.size(), 5u);
  const double d = std::sqrt(5.0);
  EXPECT_DOUBLE_EQ(h[0], (2 + d + 1) / 3); // edges 0-1, 0-2, 0-3 (0-2 counted once)
  EXPECT_DOUBLE_EQ(h[1], (2 + 1) / 2.0);
  EXPECT_DOUBLE_EQ(h[2], (1 + d + 2) / 3);
  EXPECT_DOUBLE_EQ(h[3], (1 + 2) / 2.0);
  EXPECT_EQ(h[4], 0.0);
}

TEST(SizeField, InterpolationIsThePowerMeanOfThePaper)
{
  const double a[3] = { 0, 0, 0 }, b[3] = { 1, 0, 0 }, c[3] = { 0, 1, 0 }, d[3] = { 0, 0, 1 };
  const double* corners[4] = { a, b, c, d };
  const double h[4] = { 1, 2, 4, 8 };
  // At the corners: the corner's size, for every power.
  for (double p : { 1.0, 2.0, 0.0, -1.0 })
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(interpolateSize(corners[i], corners, h, p), h[i], 1e-12) << p;
  // At the centroid (b_i = 1/4): the power means.
  const double g[3] = { 0.25, 0.25, 0.25 };
  EXPECT_NEAR(interpolateSize(g, corners, h, 1), 15.0 / 4, 1e-12);
  EXPECT_NEAR(interpolateSize(g, corners, h, 2), std::sqrt((1 + 4 + 16 + 64) / 4.0), 1e-12);
  EXPECT_NEAR(interpolateSize(g, corners, h, 0), std::pow(64.0, 0.25), 1e-12);
  EXPECT_NEAR(interpolateSize(g, corners, h, -1), 4 / (1 + 0.5 + 0.25 + 0.125), 1e-12);
  // Midpoint of edge ab, linear: (1 + 2) / 2. The orientation of the tet does not matter.
  const double m[3] = { 0.5, 0, 0 };
  const double* flipped[4] = { b, a, c, d };
  const double hf[4] = { 2, 1, 4, 8 };
  EXPECT_NEAR(interpolateSize(m, corners, h, 1), 1.5, 1e-12);
  EXPECT_NEAR(interpolateSize(m, flipped, hf, 1), 1.5, 1e-12);
  // A point outside: clamped to the nearest face's weights (never extrapolated below min h).
  const double outside[3] = { -1, -1, -1 };
  EXPECT_GE(interpolateSize(outside, corners, h, 1), 1.0);
  // Flat tet: equal weights.
  const double* flat[4] = { a, b, c, g };
  const double gz[3] = { 0.25, 0.25, 0 };
  flat[3] = gz;
  EXPECT_NEAR(interpolateSize(g, flat, h, 1), 15.0 / 4, 1e-12);
}

TEST(SizeField, ScaleAndClamp)
{
  SizeFieldOptions o;
  o.scale = 2;
  EXPECT_EQ(scaleAndClampSize(3, o), 6);
  o.minSize = 7;
  EXPECT_EQ(scaleAndClampSize(3, o), 7);
  o.maxSize = 10;
  EXPECT_EQ(scaleAndClampSize(30, o), 10);
  o.minSize = 0;
  EXPECT_EQ(scaleAndClampSize(1, o), 2);
}

namespace
{
// A path 0-1-...-(n-1) along x with spacing dx, as symmetric CSR.
void path(int n,
  double dx,
  std::vector<double>& pts,
  std::vector<std::int32_t>& off,
  std::vector<std::int32_t>& adj)
{
  pts.clear();
  off.assign(1, 0);
  adj.clear();
  for (int i = 0; i < n; ++i)
  {
    pts.insert(pts.end(), { i * dx, 0.0, 0.0 });
    if (i > 0)
      adj.push_back(i - 1);
    if (i + 1 < n)
      adj.push_back(i + 1);
    off.push_back(static_cast<std::int32_t>(adj.size()));
  }
}

// Appends triangle f: three corners within `spread` of a random point of the unit cube.
void appendRandomTriangle(std::mt19937_64& rng,
  std::uniform_real_distribution<double>& unit,
  double spread,
  int f,
  std::vector<double>& points,
  std::vector<std::int32_t>& corners)
{
  const double c[3] = { unit(rng), unit(rng), unit(rng) };
  for (int k = 0; k < 3; ++k)
  {
    for (int a = 0; a < 3; ++a)
      points.push_back(c[a] + spread * (unit(rng) - 0.5));
    corners.push_back(static_cast<std::int32_t>(3 * f + k));
  }
}
} // namespace

TEST(SizeField, GradationBoundsGrowthAlongEdges)
{
  std::vector<double> pts;
  std::vector<std::int32_t> off, adj;
  path(11, 0.1, pts, off, adj);
  std::vector<double> h(11, 1.0);
  h[0] = 0.01;
  const std::int64_t changed =
    limitGradation(pts.data(), 11, off.data(), adj.data(), 1.5, h.data());
  EXPECT_EQ(changed, 10);
  for (int i = 0; i < 11; ++i)
    EXPECT_NEAR(h[i], 0.01 + 0.5 * 0.1 * i, 1e-12) << i;
  // Off: nothing changes.
  std::vector<double> h2(11, 1.0);
  h2[0] = 0.01;
  EXPECT_EQ(limitGradation(pts.data(), 11, off.data(), adj.data(), 1.0, h2.data()), 0);
  EXPECT_EQ(h2[5], 1.0);
  // Only lowers: a large value in the middle of small ones is cut down, small ones stay.
  std::vector<double> h3(11, 0.05);
  h3[5] = 10;
  limitGradation(pts.data(), 11, off.data(), adj.data(), 1.5, h3.data());
  EXPECT_NEAR(h3[5], 0.05 + 0.05, 1e-12);
  EXPECT_EQ(h3[4], 0.05);
}

TEST(SizeField, GradationHoldsOnEveryEdgeOfARandomGraph)
{
  // Random points, each joined to its 6 nearest (symmetrised); random sizes over 100x.
  const int n = 400;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> pts(3 * n), h(n);
  for (double& x : pts)
    x = u(rng);
  for (double& x : h)
    x = std::pow(10.0, -2 + 2 * u(rng));
  std::vector<std::vector<std::int32_t>> nb(n);
  for (int i = 0; i < n; ++i)
  {
    std::vector<std::pair<double, int>> d;
    for (int j = 0; j < n; ++j)
      if (j != i)
      {
        double s = 0;
        for (int k = 0; k < 3; ++k)
          s += (pts[3 * i + k] - pts[3 * j + k]) * (pts[3 * i + k] - pts[3 * j + k]);
        d.emplace_back(s, j);
      }
    std::partial_sort(d.begin(), d.begin() + 6, d.end());
    for (int k = 0; k < 6; ++k)
    {
      nb[i].push_back(d[k].second);
      nb[d[k].second].push_back(i);
    }
  }
  std::vector<std::int32_t> off(1, 0), adj;
  for (auto& l : nb)
  {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
    adj.insert(adj.end(), l.begin(), l.end());
    off.push_back(static_cast<std::int32_t>(adj.size()));
  }
  const std::vector<double> original = h;
  limitGradation(pts.data(), n, off.data(), adj.data(), 1.3, h.data());
  int violations = 0;
  for (int i = 0; i < n; ++i)
  {
    EXPECT_LE(h[i], original[i]);
    for (std::int32_t k = off[i]; k < off[i + 1]; ++k)
    {
      const int j = adj[k];
      double s = 0;
      for (int c = 0; c < 3; ++c)
        s += (pts[3 * i + c] - pts[3 * j + c]) * (pts[3 * i + c] - pts[3 * j + c]);
      violations += h[j] > h[i] + 0.3 * std::sqrt(s) * (1 + 1e-12);
    }
  }
  EXPECT_EQ(violations, 0);
  // The smallest size is a fixed point.
  const auto m = std::min_element(original.begin(), original.end()) - original.begin();
  EXPECT_EQ(h[m], original[m]);

  // The sizes are the largest within the bound on every edge, whatever lowers them in
  // whichever order: bit for bit those of a plain relaxation over every edge until nothing
  // changes, and of the same Dijkstra over a neighbour function from every vertex.
  std::vector<double> relaxed = original;
  const double slope = 1.3 - 1; // as limitGradation has it (not 0.3)
  for (bool changed = true; changed;)
  {
    changed = false;
    for (int i = 0; i < n; ++i)
      for (std::int32_t k = off[i]; k < off[i + 1]; ++k)
      {
        const int j = adj[k];
        const double dx = pts[3 * i] - pts[3 * j], dy = pts[3 * i + 1] - pts[3 * j + 1],
                     dz = pts[3 * i + 2] - pts[3 * j + 2];
        const double bound = relaxed[i] + slope * std::sqrt(dx * dx + dy * dy + dz * dz);
        if (bound < relaxed[j])
        {
          relaxed[j] = bound;
          changed = true;
        }
      }
  }
  EXPECT_TRUE(relaxed == h);
  std::vector<double> fromSeeds = original;
  std::vector<std::int32_t> all(n), lowered;
  for (int i = 0; i < n; ++i)
    all[i] = i;
  std::int32_t stopAt = -1; // the vertex whose neighbours are not told (-1: none)
  auto neighbours = [&](std::int32_t v, std::vector<std::int32_t>& list)
  {
    list.assign(adj.begin() + off[v], adj.begin() + off[v + 1]);
    return v != stopAt;
  };
  const std::int64_t count =
    limitGradationFrom(pts.data(), n, 1.3, fromSeeds.data(), all, neighbours, lowered);
  EXPECT_TRUE(fromSeeds == h);
  EXPECT_EQ(count, static_cast<std::int64_t>(lowered.size()));
  EXPECT_GT(count, 0);
  // A neighbour function that stops leaves the sizes as they were.
  std::vector<double> stopped = original;
  stopAt = static_cast<std::int32_t>(m);
  EXPECT_EQ(limitGradationFrom(pts.data(), n, 1.3, stopped.data(), all, neighbours, lowered), -1);
  EXPECT_TRUE(stopped == original);
}

TEST(BoundarySizeFloor, FallsAtItsSlopeFromEachFace)
{
  // Two faces in z = 0: a large one (size 2, base 0.5: reaches 1.5 at slope 1) and a small
  // one (size 0.4 <= base 0.5: adds nothing).
  const double points[] = { 0, 0, 0, 4, 0, 0, 0, 4, 0, 10, 10, 0, 11, 10, 0, 10, 11, 0 };
  const std::vector<std::int32_t> corners = { 0, 1, 2, 3, 4, 5 };
  const BoundarySizeFloor floor(points, corners, { 2.0, 0.4 }, { 0.5, 0.5 }, 1.0);
  ASSERT_EQ(floor.faceCount(), 1u);
  const double onFace[] = { 1, 1, 0 };
  const double above[] = { 1, 1, 0.75 };
  const double beside[] = { -0.3, 1, 0.4 }; // nearest point of the face: (0, 1, 0)
  const double beyond[] = { 1, 1, 1.6 };
  const double nearSmall[] = { 10.2, 10.2, 0.1 };
  EXPECT_DOUBLE_EQ(floor.at(onFace), 2.0);
  EXPECT_DOUBLE_EQ(floor.at(above), 1.25);
  EXPECT_DOUBLE_EQ(floor.at(beside), 2.0 - 0.5);
  EXPECT_EQ(floor.at(beyond), 0.0);
  EXPECT_EQ(floor.at(nearSmall), 0.0);
  // atLeast is returned when the faces cannot beat it.
  EXPECT_DOUBLE_EQ(floor.at(above, 1.0), 1.25);
  EXPECT_DOUBLE_EQ(floor.at(above, 1.5), 1.5);
  // Off: slope <= 0.
  EXPECT_TRUE(BoundarySizeFloor(points, corners, { 2.0, 0.4 }, { 0.5, 0.5 }, 0.0).empty());
}

TEST(BoundarySizeFloor, IsTheLargestConeOverTheFaces)
{
  // 5000 random triangles of random sizes and bases in the unit cube, about half of them with
  // a reach (over the 2048 from which the construction's two halves run side by side); the
  // cells' answer equals the brute-force maximum of s_F - slope d(p, F) over the faces within
  // their reach (and atLeast where that is larger) at 2000 random points inside and around.
  constexpr int kFaces = 5000;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1), around(-0.3, 1.3), size(0.02, 0.3);
  std::vector<double> points, sizes, bases;
  std::vector<std::int32_t> corners;
  for (int f = 0; f < kFaces; ++f)
  {
    appendRandomTriangle(rng, unit, 0.05, f, points, corners);
    sizes.push_back(size(rng));
    bases.push_back(size(rng)); // about half the faces reach nothing (size <= base)
  }
  const double slope = 2;
  const BoundarySizeFloor floor(points.data(), corners, sizes, bases, slope);
  ASSERT_GT(floor.faceCount(), 2048u);
  ASSERT_LT(floor.faceCount(), 3000u);
  auto bruteForce = [&](const double* p)
  {
    double largest = 0;
    for (int f = 0; f < kFaces; ++f)
    {
      const double s = sizes[static_cast<std::size_t>(f)],
                   base = bases[static_cast<std::size_t>(f)];
      if (!(s > base))
        continue;
      const double* x = &points[9 * static_cast<std::size_t>(f)];
      const double value =
        s - slope * std::sqrt(geometry::pointTriangleDistanceSquared(p, x, x + 3, x + 6));
      if (value > s - slope * ((s - base) / slope))
        largest = std::max(largest, value);
    }
    return largest;
  };
  int reached = 0, raised = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const double p[3] = { around(rng), around(rng), around(rng) };
    const double expected = bruteForce(p);
    ASSERT_EQ(floor.at(p), expected) << i;
    reached += expected > 0;
    const double atLeast = 0.15;
    raised += expected > atLeast;
    ASSERT_EQ(floor.at(p, atLeast), std::max(expected, atLeast)) << i;
  }
  EXPECT_GT(reached, 200); // points inside and outside every reach occur
  EXPECT_LT(reached, 1900);
  EXPECT_GT(raised, 50); // both sides of atLeast occur
}

// 400 random triangles of random sizes in the unit cube (face 5 left out: size 0), and the
// brute-force minimum of s_F + slope d(p, F) that the ceiling must equal.
struct RandomCeilingFaces
{
  static constexpr double kSlope = 0.5;
  std::vector<double> points;
  std::vector<std::int32_t> corners;
  std::vector<double> sizes;

  explicit RandomCeilingFaces(std::mt19937_64& rng)
  {
    std::uniform_real_distribution<double> unit(0, 1), size(0.01, 0.2);
    for (int f = 0; f < 400; ++f)
    {
      appendRandomTriangle(rng, unit, 0.1, f, points, corners);
      sizes.push_back(size(rng));
    }
    sizes[5] = 0;
  }

  double bruteForce(const double* p) const
  {
    double smallest = 1e300;
    for (int f = 0; f < 400; ++f)
    {
      if (f == 5)
        continue;
      const double* x = &points[9 * static_cast<std::size_t>(f)];
      const double d = std::sqrt(geometry::pointTriangleDistanceSquared(p, x, x + 3, x + 6));
      smallest = std::min(smallest, sizes[static_cast<std::size_t>(f)] + kSlope * d);
    }
    return smallest;
  }
};

TEST(BoundarySizeCeiling, IsTheSmallestConeOverTheFaces)
{
  // The answer (from the cells' lists inside the faces' box, from the tree outside it) equals
  // the brute-force minimum (and atMost where that is smaller) at 2000 random points inside
  // and around.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1), around(-0.5, 1.5);
  const RandomCeilingFaces faces(rng);
  const double slope = RandomCeilingFaces::kSlope;
  const BoundarySizeCeiling ceiling(faces.points.data(), faces.corners, faces.sizes, slope);
  ASSERT_FALSE(ceiling.empty());
  auto bruteForce = [&](const double* p) { return faces.bruteForce(p); };
  int capped = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const double p[3] = { around(rng), around(rng), around(rng) };
    const double expected = bruteForce(p);
    ASSERT_EQ(ceiling.at(p, 1e300), expected) << i;
    const double atMost = 0.15;
    capped += expected >= atMost;
    ASSERT_EQ(ceiling.at(p, atMost), std::min(expected, atMost)) << i;
  }
  EXPECT_GT(capped, 100); // both sides of atMost occur
  EXPECT_LT(capped, 1900);
  // Points among the faces with bounds on both sides of the answer: the per-cell lower bounds
  // that answer most queries without the tree must never answer one wrongly.
  std::uniform_real_distribution<double> bound(0.01, 0.3);
  int early = 0;
  for (int i = 0; i < 20000; ++i)
  {
    const double p[3] = { unit(rng), unit(rng), unit(rng) };
    const double expected = bruteForce(p);
    const double atMost = bound(rng);
    early += expected >= atMost;
    ASSERT_EQ(ceiling.at(p, atMost), std::min(expected, atMost)) << i;
  }
  EXPECT_GT(early, 2000);
  EXPECT_TRUE(BoundarySizeCeiling(faces.points.data(), faces.corners, faces.sizes, 0.0).empty());
}

TEST(BoundarySizeCeiling, ListsMadeForASmallBoundAnswerLargerOnes)
{
  // A cell's list stops a little above the atMost of the query that made it; a later query
  // with a larger atMost must make it again, not read the short one. The cells of 1000 random
  // points are first queried with a small atMost here, then at the same points with larger ones.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  const RandomCeilingFaces faces(rng);
  const BoundarySizeCeiling ceiling(
    faces.points.data(), faces.corners, faces.sizes, RandomCeilingFaces::kSlope);
  std::vector<double> at;
  for (int i = 0; i < 3000; ++i)
    at.push_back(unit(rng));
  int below = 0, cut = 0;
  for (double atMost : { 0.012, 0.05, 0.1, 0.2, 1e300 })
  {
    for (std::size_t i = 0; i + 2 < at.size(); i += 3)
    {
      const double p[3] = { at[i], at[i + 1], at[i + 2] };
      const double expected = faces.bruteForce(p);
      below += expected < atMost;
      cut += atMost < 1e300 && expected > 1.25 * atMost; // beyond the first lists' limit
      ASSERT_EQ(ceiling.at(p, atMost), std::min(expected, atMost)) << i << " " << atMost;
    }
  }
  EXPECT_GT(below, 1000); // the faces decide most answers, not atMost
  EXPECT_GT(cut, 100);
}
