// The perturbation order that makes the Delaunay of a surface's points pick the surface's own
// diagonals of co-circular planar quads (PerturbationOrder.h), and the Delaunay kernel's
// perturbationRank option that applies it.
#include "Delaunay.h"
#include "PerturbationOrder.h"
#include "SurfaceInput.h"
#include "TetMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace
{
using tetmesher::VertexId;

struct Points
{
  std::vector<double> coords;
  std::vector<std::int32_t> triangles;
  VertexId add(double x, double y, double z)
  {
    // push_back, not insert of a list: GCC 12 warns (-Wstringop-overflow, a false positive).
    coords.push_back(x);
    coords.push_back(y);
    coords.push_back(z);
    return static_cast<VertexId>(coords.size() / 3 - 1);
  }
  VertexId count() const { return static_cast<VertexId>(coords.size() / 3); }
};

// A box of nx x ny x nz unit cells, each face square split by a diagonal chosen at random
// (seeded), so that about half of them disagree with any fixed tie-break.
Points randomDiagonalBox(int nx, int ny, int nz, std::uint32_t seed)
{
  Points s;
  const int n[3] = { nx, ny, nz };
  std::map<std::array<int, 3>, VertexId> ids;
  auto id = [&](const std::array<int, 3>& g)
  {
    auto it = ids.find(g);
    if (it != ids.end())
      return it->second;
    const VertexId v = s.add(g[0], g[1], g[2]);
    ids.emplace(g, v);
    return v;
  };
  std::mt19937 random(seed);
  for (int axis = 0; axis < 3; ++axis)
  {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < n[a1]; ++i)
        for (int j = 0; j < n[a2]; ++j)
        {
          std::array<int, 3> g[4];
          for (auto& c : g)
            c[axis] = side ? n[axis] : 0;
          g[0][a1] = i, g[0][a2] = j;
          g[1][a1] = i + 1, g[1][a2] = j;
          g[2][a1] = i + 1, g[2][a2] = j + 1;
          g[3][a1] = i, g[3][a2] = j + 1;
          VertexId v[4] = { id(g[0]), id(g[1]), id(g[2]), id(g[3]) };
          // Outward: (a1, a2, axis) is right-handed, so v0 v1 v2 faces +axis.
          if (side == 0)
            std::swap(v[1], v[3]);
          if (random() % 2)
            s.triangles.insert(s.triangles.end(), { v[0], v[1], v[2], v[0], v[2], v[3] });
          else
            s.triangles.insert(s.triangles.end(), { v[0], v[1], v[3], v[1], v[2], v[3] });
        }
  }
  return s;
}

tetmesher::SurfaceInput surfaceOf(const Points& s)
{
  tetmesher::SurfaceInput surface;
  EXPECT_EQ(tetmesher::buildSurfaceInput(s.coords.data(),
              s.count(),
              s.triangles.data(),
              static_cast<std::int32_t>(s.triangles.size() / 3),
              surface),
    "");
  return surface;
}

tetmesher::TetMesh delaunayOf(const Points& s, const VertexId* rank)
{
  tetmesher::TetMesh mesh;
  tetmesher::DelaunayOptions options;
  options.perturbationRank = rank;
  EXPECT_TRUE(tetmesher::buildDelaunay(mesh, s.coords.data(), s.count(), options).ok);
  return mesh;
}

std::set<std::uint64_t> edgesOf(const tetmesher::TetMesh& mesh)
{
  std::set<std::uint64_t> edges;
  for (tetmesher::TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (!mesh.isDeleted(t))
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          edges.insert(tetmesher::edgeKey(mesh.vertex(t, i), mesh.vertex(t, j)));
  return edges;
}

int missingInputEdges(const tetmesher::SurfaceInput& surface, const tetmesher::TetMesh& mesh)
{
  const std::set<std::uint64_t> edges = edgesOf(mesh);
  int missing = 0;
  for (const auto& e : surface.edges)
    missing += edges.count(tetmesher::edgeKey(e[0], e[1])) == 0;
  return missing;
}

std::vector<std::array<VertexId, 4>> sortedTets(const tetmesher::TetMesh& mesh,
  const std::vector<VertexId>& relabel)
{
  std::vector<std::array<VertexId, 4>> tets;
  for (tetmesher::TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    std::array<VertexId, 4> v;
    for (int i = 0; i < 4; ++i)
    {
      const VertexId id = mesh.vertex(t, i);
      v[i] = id < static_cast<VertexId>(relabel.size()) ? relabel[id] : id;
    }
    std::sort(v.begin(), v.end());
    tets.push_back(v);
  }
  std::sort(tets.begin(), tets.end());
  return tets;
}

// A bipyramid over the planar quad (a, c, b, d) in z = 0 split by the input diagonal ab, with
// apex e above: 5 points, 6 triangles.
Points bipyramid(const double quad[4][2], bool diagonalAB)
{
  Points s;
  const VertexId a = s.add(quad[0][0], quad[0][1], 0), c = s.add(quad[1][0], quad[1][1], 0),
                 b = s.add(quad[2][0], quad[2][1], 0), d = s.add(quad[3][0], quad[3][1], 0);
  const VertexId e = s.add(0.1, 0.2, 1);
  s.triangles = { e, a, c, e, c, b, e, b, d, e, d, a };
  if (diagonalAB)
    s.triangles.insert(s.triangles.end(), { a, b, c, a, d, b });
  else
    s.triangles.insert(s.triangles.end(), { c, d, b, c, a, d });
  return s;
}

} // namespace

TEST(PerturbationOrder, SquareQuadTakesEitherInputDiagonal)
{
  const double square[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  for (bool diagonalAB : { true, false })
  {
    const Points s = bipyramid(square, diagonalAB);
    const tetmesher::SurfaceInput surface = surfaceOf(s);
    const tetmesher::PerturbationOrder order =
      tetmesher::perturbationOrderForSurface(s.coords.data(), surface);
    EXPECT_EQ(order.quads, 1);
    EXPECT_EQ(order.satisfied, 1);
    ASSERT_EQ(order.rank.size(), 5u);
    EXPECT_EQ(missingInputEdges(surface, delaunayOf(s, order.rank.data())), 0)
      << "diagonal ab: " << diagonalAB;
  }
  // By ids alone one of the two diagonals is missing: the order is what recovers it.
  int missingByIds = 0;
  for (bool diagonalAB : { true, false })
  {
    const Points s = bipyramid(square, diagonalAB);
    missingByIds += missingInputEdges(surfaceOf(s), delaunayOf(s, nullptr));
  }
  EXPECT_EQ(missingByIds, 1);
}

TEST(PerturbationOrder, QuadsThatAreNoTieAreLeftAlone)
{
  // Planar but not co-circular (a kite), and co-circular but not planar.
  const double kite[4][2] = { { 0, 0 }, { 1, -1 }, { 3, 0 }, { 1, 1 } };
  Points s = bipyramid(kite, true);
  EXPECT_EQ(tetmesher::perturbationOrderForSurface(s.coords.data(), surfaceOf(s)).quads, 0);
  const double square[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  s = bipyramid(square, true);
  s.coords[3 * 3 + 2] = 1e-9; // d lifted off the plane of a, b, c
  const auto order = tetmesher::perturbationOrderForSurface(s.coords.data(), surfaceOf(s));
  EXPECT_EQ(order.quads, 0);
  EXPECT_TRUE(order.rank.empty());
}

TEST(PerturbationOrder, RandomDiagonalBoxKeepsEveryInputEdge)
{
  for (std::uint32_t seed : { 1u, 2u, 3u })
  {
    const Points s = randomDiagonalBox(6, 5, 4, seed);
    const tetmesher::SurfaceInput surface = surfaceOf(s);
    const tetmesher::PerturbationOrder order =
      tetmesher::perturbationOrderForSurface(s.coords.data(), surface);
    EXPECT_EQ(order.quads, 2 * (6 * 5 + 5 * 4 + 4 * 6)) << "seed " << seed;
    EXPECT_EQ(order.satisfied, order.quads) << "seed " << seed;
    std::vector<VertexId> sorted = order.rank;
    std::sort(sorted.begin(), sorted.end());
    for (VertexId v = 0; v < s.count(); ++v)
      ASSERT_EQ(sorted[v], v) << "not a permutation";
    EXPECT_EQ(missingInputEdges(surface, delaunayOf(s, order.rank.data())), 0) << "seed " << seed;
    EXPECT_GT(missingInputEdges(surface, delaunayOf(s, nullptr)), 10) << "seed " << seed;
  }
}

TEST(PerturbationOrder, RankedMeshIsTheDelaunayOfTheRenumberedPoints)
{
  // perturbationRank must act exactly as renumbering the points by rank: the same tets. The
  // second box has over 16384 points, so its last round goes in two halves of space.
  for (const std::array<int, 3>& cells : { std::array<int, 3>{ 5, 4, 3 }, { 80, 80, 20 } })
  {
    const Points s = randomDiagonalBox(cells[0], cells[1], cells[2], 7);
    const tetmesher::PerturbationOrder order =
      tetmesher::perturbationOrderForSurface(s.coords.data(), surfaceOf(s));
    ASSERT_FALSE(order.rank.empty());
    Points renumbered = s;
    std::vector<VertexId> byRank(s.count());
    for (VertexId v = 0; v < s.count(); ++v)
    {
      byRank[order.rank[v]] = v;
      for (int k = 0; k < 3; ++k)
        renumbered.coords[3 * order.rank[v] + k] = s.coords[3 * v + k];
    }
    const auto ranked = sortedTets(delaunayOf(s, order.rank.data()), {});
    const auto plain = sortedTets(delaunayOf(renumbered, nullptr), byRank);
    EXPECT_EQ(ranked, plain) << s.count() << " points";
    EXPECT_NE(ranked, sortedTets(delaunayOf(s, nullptr), {})) << s.count() << " points";
  }
}
