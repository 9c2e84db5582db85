// triangulatePolygon: n-2 triangles of the polygon's own corners that tile it exactly once in
// its orientation (checked by exact 2D orientations, the edge multiplicities and the area),
// for convex and non-convex polygons in tilted planes, corners on a line, a keyhole around a
// hole; a fan for a polygon that crosses itself.
#include "PolygonTriangulation.h"
#include "Predicates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

using tetmesher::triangulatePolygon;

namespace
{
struct Polygon
{
  std::vector<double> points; // xyz per corner
  std::vector<std::int64_t> ids;
};

// 2D corners (u, v) placed in the plane through `origin` spanned by e1, e2.
Polygon inPlane(const std::vector<std::pair<double, double>>& uv,
  const double* origin,
  const double* e1,
  const double* e2)
{
  Polygon p;
  for (const auto& [u, v] : uv)
  {
    for (int k = 0; k < 3; ++k)
      p.points.push_back(origin[k] + u * e1[k] + v * e2[k]);
    p.ids.push_back(static_cast<std::int64_t>(p.ids.size()));
  }
  return p;
}

double shoelace(const std::vector<std::pair<double, double>>& uv)
{
  double twice = 0;
  for (std::size_t i = 0; i < uv.size(); ++i)
  {
    const auto& a = uv[i];
    const auto& b = uv[(i + 1) % uv.size()];
    twice += a.first * b.second - b.first * a.second;
  }
  return 0.5 * twice;
}

// The invariants of a triangulation of a simple polygon given in the (u, v) plane with a
// positive area: n-2 triangles, each turning left (exactly, in the plane z = 0), polygon edges
// used once in their direction, diagonals twice in opposite directions, areas adding up.
void expectTiling(const std::vector<std::pair<double, double>>& uv, const char* what)
{
  const double origin[3] = { 0, 0, 0 }, e1[3] = { 1, 0, 0 }, e2[3] = { 0, 1, 0 };
  const Polygon p = inPlane(uv, origin, e1, e2);
  std::vector<std::int32_t> tris;
  triangulatePolygon(p.points.data(),
    static_cast<std::int64_t>(p.ids.size()),
    p.ids.data(),
    static_cast<std::int64_t>(p.ids.size()),
    tris);
  const int n = static_cast<int>(uv.size());
  ASSERT_EQ(tris.size(), static_cast<std::size_t>(3 * (n - 2))) << what;
  std::map<std::pair<int, int>, int> directed;
  double area = 0;
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    const double* a = &p.points[3 * static_cast<std::size_t>(tris[t])];
    const double* b = &p.points[3 * static_cast<std::size_t>(tris[t + 1])];
    const double* c = &p.points[3 * static_cast<std::size_t>(tris[t + 2])];
    EXPECT_GT(tetmesher::predicates::orient2d(a, b, c, 2), 0) << what << ": triangle " << t / 3;
    area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
    for (int k = 0; k < 3; ++k)
      ++directed[{ tris[t + k], tris[t + (k + 1) % 3] }];
  }
  for (const auto& [edge, uses] : directed)
  {
    EXPECT_EQ(uses, 1) << what << ": edge " << edge.first << "-" << edge.second;
    const bool boundary = (edge.first + 1) % n == edge.second;
    EXPECT_EQ(directed.count({ edge.second, edge.first }), boundary ? 0u : 1u)
      << what << ": edge " << edge.first << "-" << edge.second;
  }
  for (int i = 0; i < n; ++i)
    EXPECT_EQ(directed.count({ i, (i + 1) % n }), 1u) << what << ": polygon edge " << i;
  EXPECT_NEAR(area, shoelace(uv), 1e-12 * std::fabs(shoelace(uv))) << what;
}
} // namespace

TEST(PolygonTriangulation, ConvexAndStarShapedPolygons)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> radius(0.2, 1.0);
  for (int n = 4; n <= 40; ++n)
  {
    std::vector<std::pair<double, double>> convex, star;
    for (int i = 0; i < n; ++i)
    {
      const double angle = 2 * M_PI * i / n;
      convex.emplace_back(std::cos(angle), std::sin(angle));
      const double r = radius(rng);
      star.emplace_back(r * std::cos(angle), r * std::sin(angle));
    }
    expectTiling(convex, "convex");
    expectTiling(star, "star-shaped");
  }
}

TEST(PolygonTriangulation, CombsSpiralsAndCornersOnALine)
{
  // A comb: teeth up from a base, the kind of polygon a fan from corner 0 gets wrong.
  std::vector<std::pair<double, double>> comb = { { 0, 0 }, { 9, 0 } };
  for (int t = 4; t >= 0; --t)
  {
    comb.emplace_back(2 * t + 1, 3);
    comb.emplace_back(2 * t + 0.5, 1);
  }
  expectTiling(comb, "comb");
  // L shape, and a square with corners in the middle of two sides (collinear triples).
  expectTiling({ { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } }, "L");
  expectTiling({ { 0, 0 }, { 0.5, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 }, { 0, 0.5 } },
    "square with corners on its sides");
  // A spiral strip (very non-convex).
  std::vector<std::pair<double, double>> spiral;
  const int turns = 60;
  for (int i = 0; i < turns; ++i)
  {
    const double a = 0.15 * i, r = 1 + 0.1 * i;
    spiral.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  for (int i = turns - 1; i >= 0; --i)
  {
    const double a = 0.15 * i, r = 1.05 + 0.1 * i;
    spiral.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  if (shoelace(spiral) < 0)
    std::reverse(spiral.begin(), spiral.end());
  expectTiling(spiral, "spiral");
}

TEST(PolygonTriangulation, TiltedPlanesKeepTheOrientation)
{
  // The same pentagon in planes of every orientation, and reversed: each triangle's normal
  // points along the polygon's (Newell) normal.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss;
  const std::vector<std::pair<double, double>> uv = {
    { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 0.4 }, { 0, 1 }
  };
  for (int trial = 0; trial < 200; ++trial)
  {
    double e1[3], e2[3], origin[3];
    for (int k = 0; k < 3; ++k)
    {
      e1[k] = gauss(rng);
      e2[k] = gauss(rng);
      origin[k] = gauss(rng);
    }
    Polygon p = inPlane(uv, origin, e1, e2);
    if (trial % 2)
      std::reverse(p.ids.begin(), p.ids.end());
    const double normal[3] = {
      e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]
    };
    const double sign = trial % 2 ? -1 : 1;
    std::vector<std::int32_t> tris;
    triangulatePolygon(p.points.data(), 5, p.ids.data(), 5, tris);
    ASSERT_EQ(tris.size(), 9u);
    for (std::size_t t = 0; t < tris.size(); t += 3)
    {
      const double* a = &p.points[3 * static_cast<std::size_t>(p.ids[tris[t]])];
      const double* b = &p.points[3 * static_cast<std::size_t>(p.ids[tris[t + 1]])];
      const double* c = &p.points[3 * static_cast<std::size_t>(p.ids[tris[t + 2]])];
      double dot = 0;
      for (int k = 0; k < 3; ++k)
      {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        dot += normal[k] * ((b[k1] - a[k1]) * (c[k2] - a[k2]) - (b[k2] - a[k2]) * (c[k1] - a[k1]));
      }
      EXPECT_GT(sign * dot, 0) << trial;
    }
  }
}

TEST(PolygonTriangulation, QuadGetsTheBetterDiagonal)
{
  // Whether the triangles of `tris` use the diagonal 1-3 of a quad.
  auto usesDiagonal13 = [](const std::vector<std::int32_t>& tris)
  {
    for (std::size_t t = 0; t < tris.size(); t += 3)
    {
      int hits = 0;
      for (int k = 0; k < 3; ++k)
        hits += tris[t + k] == 1 || tris[t + k] == 3;
      if (hits == 2)
        return true;
    }
    return false;
  };
  const std::int64_t ids[] = { 0, 1, 2, 3 };
  // A flat kite: the long diagonal 0-2 would make two slivers, the short one 1-3 two fat
  // triangles.
  const double flat[] = { 0, 0, 0, 1, -0.2, 0, 2, 0, 0, 1, 0.2, 0 };
  std::vector<std::int32_t> tris;
  triangulatePolygon(flat, 4, ids, 4, tris);
  ASSERT_EQ(tris.size(), 6u);
  EXPECT_TRUE(usesDiagonal13(tris));
  // A tall kite: now 0-2 is the short diagonal.
  const double tall[] = { 0, 0, 0, 1, -2, 0, 2, 0, 0, 1, 2, 0 };
  tris.clear();
  triangulatePolygon(tall, 4, ids, 4, tris);
  ASSERT_EQ(tris.size(), 6u);
  EXPECT_FALSE(usesDiagonal13(tris));
}

TEST(PolygonTriangulation, KeyholeAroundAHoleAndSelfCrossingFan)
{
  // Testing/Data/defects/keyhole-polygon.off's top: around a square hole through a slit, the
  // slit's corners twice (points 4 and 8). The triangles cover the ring once: 0.75 in area.
  const double points[] = {
    0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1, 0.25, 0.25, 1, 0.75, 0.25, 1, 0.75, 0.75, 1, 0.25, 0.75, 1
  };
  const std::int64_t ids[] = { 0, 1, 2, 3, 0, 4, 7, 6, 5, 4 };
  std::vector<std::int32_t> tris;
  triangulatePolygon(points, 8, ids, 10, tris);
  ASSERT_EQ(tris.size(), 24u);
  double area = 0;
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    const double* a = points + 3 * ids[tris[t]];
    const double* b = points + 3 * ids[tris[t + 1]];
    const double* c = points + 3 * ids[tris[t + 2]];
    EXPECT_GT(tetmesher::predicates::orient2d(a, b, c, 2), 0) << t / 3;
    area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
  }
  EXPECT_DOUBLE_EQ(area, 0.75);

  // A bow tie crosses itself: no ear cut makes sense; the fan from corner 0.
  const double bow[] = { 0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0 };
  const std::int64_t four[] = { 0, 1, 2, 3 };
  tris.clear();
  triangulatePolygon(bow, 4, four, 4, tris);
  EXPECT_EQ(tris, (std::vector<std::int32_t>{ 0, 1, 2, 0, 2, 3 }));
  // An id out of range: the fan too (the input check names the id); fewer than 3 corners
  // append nothing.
  const std::int64_t outOfRange[] = { 0, 1, 7, 3 };
  tris.clear();
  triangulatePolygon(bow, 4, outOfRange, 4, tris);
  EXPECT_EQ(tris, (std::vector<std::int32_t>{ 0, 1, 2, 0, 2, 3 }));
  triangulatePolygon(bow, 4, four, 2, tris);
  EXPECT_EQ(tris.size(), 6u);
  // Beyond kMaxEarClippedCorners corners: the fan, at once.
  std::vector<double> many;
  std::vector<std::int64_t> manyIds;
  const int n = static_cast<int>(tetmesher::kMaxEarClippedCorners) + 1;
  for (int i = 0; i < n; ++i)
  {
    many.insert(many.end(), { std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0.0 });
    manyIds.push_back(i);
  }
  tris.clear();
  triangulatePolygon(many.data(), n, manyIds.data(), n, tris);
  ASSERT_EQ(tris.size(), static_cast<std::size_t>(3 * (n - 2)));
  EXPECT_EQ(tris[3 * (n - 3) + 2], n - 1);
  EXPECT_EQ(tris[3 * (n - 3)], 0);
}

TEST(PolygonTriangulation, AnyPolygonGivesNMinus2TrianglesOfItsCorners)
{
  // Random polygons, most of them crossing themselves, with repeated and collinear corners
  // (coordinates on a coarse grid) and out-of-plane noise: always n-2 triangles of corner
  // indices in range, nothing else (the sanitizer builds run this too).
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> grid(0, 4), size(3, 24), pick(0, 39);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  std::vector<double> points;
  for (int i = 0; i < 40; ++i)
    points.insert(points.end(), { double(grid(rng)), double(grid(rng)), noise(rng) * (i % 3) });
  for (int trial = 0; trial < 20000; ++trial)
  {
    const int n = size(rng);
    std::vector<std::int64_t> ids;
    for (int i = 0; i < n; ++i)
      ids.push_back(pick(rng));
    std::vector<std::int32_t> tris = { 7 }; // appended after what is there
    triangulatePolygon(points.data(), 40, ids.data(), n, tris);
    ASSERT_EQ(tris.size(), static_cast<std::size_t>(1 + 3 * (n - 2))) << trial;
    ASSERT_EQ(tris[0], 7);
    for (std::size_t k = 1; k < tris.size(); ++k)
      ASSERT_TRUE(tris[k] >= 0 && tris[k] < n) << trial;
  }
}
