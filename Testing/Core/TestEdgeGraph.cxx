// EdgeGraph, the refinement's edge adjacency: against the unique edges gathered independently
// (a std::set of vertex pairs), its documented order, and the same arrays whether its halves run
// on one thread or two.
#include "Delaunay.h"
#include "EdgeGraph.h"
#include "PointSets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

using namespace tetmesher;
using namespace tetmesher::testing;

namespace
{

// A Delaunay mesh with deleted slots in it (the box's tets, and some more), as the refinement
// builds the graph on.
TetMesh meshWithHoles(int points)
{
  TetMesh mesh = randomPoints(points, 11);
  const DelaunayResult r = buildDelaunay(mesh);
  EXPECT_TRUE(r.ok);
  // Every 7th live tet deleted: the graph covers the live ones only.
  for (TetId t = 0; t < mesh.tetCapacity(); t += 7)
    if (!mesh.isDeleted(t))
      mesh.deleteTet(t);
  return mesh;
}

void expectGraphOf(const TetMesh& mesh, const EdgeGraph& g)
{
  static const int kEdges[6][2] = { { 0, 1 }, { 0, 2 }, { 0, 3 }, { 1, 2 }, { 1, 3 }, { 2, 3 } };
  const std::size_t nv = static_cast<std::size_t>(mesh.vertexCount());
  std::vector<std::set<VertexId>> expected(nv);
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (!mesh.isDeleted(t))
      for (const auto& e : kEdges)
      {
        const VertexId a = mesh.vertex(t, e[0]), b = mesh.vertex(t, e[1]);
        expected[static_cast<std::size_t>(a)].insert(b);
        expected[static_cast<std::size_t>(b)].insert(a);
      }
  ASSERT_EQ(g.offsets.size(), nv + 1);
  ASSERT_EQ(g.targets.size(), static_cast<std::size_t>(g.offsets[nv]));
  ASSERT_EQ(g.tetOf.size(), g.targets.size());
  for (std::size_t v = 0; v < nv; ++v)
  {
    const std::vector<VertexId> list(
      g.targets.begin() + g.offsets[v], g.targets.begin() + g.offsets[v + 1]);
    // The same neighbours, each once.
    EXPECT_EQ(std::set<VertexId>(list.begin(), list.end()), expected[v]) << "vertex " << v;
    EXPECT_EQ(list.size(), expected[v].size()) << "vertex " << v;
    // Smaller ones first, increasing; then larger ones.
    std::size_t smaller = 0;
    while (smaller < list.size() && list[smaller] < static_cast<VertexId>(v))
      ++smaller;
    EXPECT_TRUE(std::is_sorted(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(smaller)));
    for (std::size_t k = smaller; k < list.size(); ++k)
      EXPECT_GT(list[k], static_cast<VertexId>(v));
    // Each entry's tet is live and has the edge.
    for (std::int32_t k = g.offsets[v]; k < g.offsets[v + 1]; ++k)
    {
      const TetId t = g.tetOf[static_cast<std::size_t>(k)];
      ASSERT_FALSE(mesh.isDeleted(t));
      int found = 0;
      for (int i = 0; i < 4; ++i)
        found += mesh.vertex(t, i) == static_cast<VertexId>(v) ||
          mesh.vertex(t, i) == g.targets[static_cast<std::size_t>(k)];
      EXPECT_EQ(found, 2) << "vertex " << v << " entry " << k;
    }
  }
}

} // namespace

TEST(EdgeGraph, SmallMeshMatchesTheUniqueEdges)
{
  const TetMesh mesh = meshWithHoles(500);
  EdgeGraph g;
  g.build(mesh, false);
  expectGraphOf(mesh, g);
}

TEST(EdgeGraph, HalvesGiveTheSameArraysAsOneThread)
{
  // Large enough for the halves (65536 tet slots or more).
  const TetMesh mesh = meshWithHoles(20000);
  ASSERT_GE(mesh.tetCapacity(), 65536);
  EdgeGraph one, two;
  one.build(mesh, false);
  expectGraphOf(mesh, one);
  for (int run = 0; run < 3; ++run)
  {
    two.build(mesh, true); // rebuilt in place, as the refinement does every round
    EXPECT_EQ(two.offsets, one.offsets);
    EXPECT_EQ(two.targets, one.targets);
    EXPECT_EQ(two.tetOf, one.tetOf);
  }
}

TEST(EdgeGraph, ChunksGiveTheSameArrays)
{
  // Chunks far smaller than the mesh (some of a single block of 1024 vertices), on one thread
  // and on two, against one chunk for everything.
  const TetMesh mesh = meshWithHoles(20000);
  EdgeGraph whole, chunked;
  whole.chunkHalfEdges = std::size_t{ 1 } << 30;
  whole.build(mesh, false);
  expectGraphOf(mesh, whole);
  chunked.maxChunks = std::size_t{ 1 } << 30; // the chunks as small as asked
  for (std::size_t chunk : { std::size_t{ 1 }, std::size_t{ 5000 }, std::size_t{ 40000 } })
    for (bool twoThreads : { false, true })
    {
      chunked.chunkHalfEdges = chunk;
      chunked.build(mesh, twoThreads);
      EXPECT_EQ(chunked.offsets, whole.offsets) << chunk << " " << twoThreads;
      EXPECT_EQ(chunked.targets, whole.targets) << chunk << " " << twoThreads;
      EXPECT_EQ(chunked.tetOf, whole.tetOf) << chunk << " " << twoThreads;
    }
  // At most maxChunks chunks however small chunkHalfEdges is (a chunk is whole blocks of 1024
  // vertices, so one block may make it larger): the same arrays.
  for (std::size_t maxChunks : { std::size_t{ 0 }, std::size_t{ 1 }, std::size_t{ 3 } })
  {
    chunked.chunkHalfEdges = 1;
    chunked.maxChunks = maxChunks;
    chunked.build(mesh, true);
    EXPECT_EQ(chunked.offsets, whole.offsets) << maxChunks;
    EXPECT_EQ(chunked.targets, whole.targets) << maxChunks;
    EXPECT_EQ(chunked.tetOf, whole.tetOf) << maxChunks;
  }
}
