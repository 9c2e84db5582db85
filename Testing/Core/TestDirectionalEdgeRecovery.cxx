// Directional recovery of missing edges (DirectionalEdgeRecovery.h) on Delaunay meshes of
// random and lattice points: the edge is there when it says so, the mesh stays a valid
// triangulation of the same region, kept edges are never removed, and a segment through a
// vertex is refused without a move.
#include "Delaunay.h"
#include "DirectionalEdgeRecovery.h"
#include "MeshTopology.h"
#include "MeshValidation.h"
#include "PointSets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <utility>

using namespace tetmesher;

namespace
{

struct Built
{
  TetMesh mesh;
  VertexId pointCount = 0;
};

Built delaunayOf(TetMesh points)
{
  Built b;
  b.pointCount = points.vertexCount();
  b.mesh = std::move(points);
  const DelaunayResult r = buildDelaunay(b.mesh);
  EXPECT_TRUE(r.ok) << r.error;
  return b;
}

std::set<std::pair<VertexId, VertexId>> edgesOf(const TetMesh& mesh)
{
  std::set<std::pair<VertexId, VertexId>> edges;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (!mesh.isDeleted(t))
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          edges.insert(std::minmax(mesh.vertex(t, i), mesh.vertex(t, j)));
  return edges;
}

// The mesh is a triangulation of the box (every tet positive, adjacency symmetric) with all
// points and the box's volume.
void expectValid(const TetMesh& mesh, VertexId pointCount, long double volume)
{
  EXPECT_EQ(checkOrientation(mesh), "");
  EXPECT_EQ(checkAdjacency(mesh), "");
  EXPECT_EQ(checkVerticesPresent(mesh, pointCount), "");
  const long double now = volumeWithoutVertices(mesh, mesh.vertexCount());
  EXPECT_NEAR(static_cast<double>(now), static_cast<double>(volume), 1e-9 * volume);
}

double distance(const TetMesh& mesh, VertexId a, VertexId b)
{
  const double *p = mesh.point(a), *q = mesh.point(b);
  return std::sqrt(
    (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

} // namespace

// Short random segments between points of a random set: every success is a real edge, every
// call (success or not) leaves a valid triangulation, and most segments are recovered.
TEST(DirectionalEdgeRecovery, RecoversRandomSegmentsAndKeepsTheMeshValid)
{
  Built b = delaunayOf(tetmesher::testing::randomPoints(300, 7));
  TetMesh& mesh = b.mesh;
  const long double volume = volumeWithoutVertices(mesh, mesh.vertexCount());
  VertexTetIndex index;
  index.rebuild(mesh);
  std::mt19937 gen(11);
  std::uniform_int_distribution<VertexId> pick(0, b.pointCount - 1);
  // Short segments, as the surface edges a Delaunay mesh misses (the points are ~0.15 apart).
  constexpr double kNear = 0.25;
  int tried = 0, recovered = 0, flips23 = 0, removals = 0;
  for (int k = 0; k < 20000 && tried < 200; ++k)
  {
    const VertexId a = pick(gen), c = pick(gen);
    if (a == c || findEdge(mesh, index, a, c) >= 0 || distance(mesh, a, c) > kNear)
      continue;
    ++tried;
    const bool ok = flipEdgeIntoMesh(
      mesh,
      index,
      a,
      c,
      [](VertexId, VertexId) { return false; },
      [&](const FlipCandidate& move, bool isFlip23)
      {
        replaceTets(mesh, index, move.oldTets, move.newTets);
        ++(isFlip23 ? flips23 : removals);
      });
    EXPECT_EQ(ok, findEdge(mesh, index, a, c) >= 0) << a << " " << c;
    recovered += ok;
  }
  expectValid(mesh, b.pointCount, volume);
  EXPECT_GT(tried, 150);
  // Not all: that is what the greedy search and Steiner points are for.
  EXPECT_GT(recovered, tried / 2) << recovered << " of " << tried;
  EXPECT_GT(flips23, 0);
  EXPECT_GT(removals, 0);
}

// A segment across a single face whose 2-3 flip is valid takes exactly that flip.
TEST(DirectionalEdgeRecovery, OneFaceApartIsOneFlip)
{
  Built b = delaunayOf(tetmesher::testing::randomPoints(200, 3));
  TetMesh& mesh = b.mesh;
  VertexTetIndex index;
  index.rebuild(mesh);
  int checked = 0;
  for (TetId t = 0; t < mesh.tetCapacity() && checked < 20; ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    for (int f = 0; f < 4 && checked < 20; ++f)
    {
      FlipCandidate flip;
      const FaceRef n = mesh.neighbor(t, f);
      if (n == kNoNeighbor || !flip23Candidate(mesh, t, f, FlipCost(), flip))
        continue;
      const VertexId a = mesh.vertex(t, f), s = mesh.vertex(faceTet(n), faceIndex(n));
      if (a >= b.pointCount || s >= b.pointCount || findEdge(mesh, index, a, s) >= 0)
        continue;
      TetMesh copy = mesh;
      VertexTetIndex copyIndex;
      copyIndex.rebuild(copy);
      int moves = 0;
      bool lastWasFlip23 = false;
      ASSERT_TRUE(flipEdgeIntoMesh(
        copy,
        copyIndex,
        a,
        s,
        [](VertexId, VertexId) { return false; },
        [&](const FlipCandidate& move, bool isFlip23)
        {
          replaceTets(copy, copyIndex, move.oldTets, move.newTets);
          ++moves;
          lastWasFlip23 = isFlip23;
        }));
      EXPECT_EQ(moves, 1);
      EXPECT_TRUE(lastWasFlip23);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 20);
}

// With every edge of the mesh at the start kept, none of them may go (edges made by the flips
// may).
TEST(DirectionalEdgeRecovery, NeverRemovesAKeptEdge)
{
  Built b = delaunayOf(tetmesher::testing::randomPoints(300, 5));
  TetMesh& mesh = b.mesh;
  const auto initial = edgesOf(mesh);
  VertexTetIndex index;
  index.rebuild(mesh);
  std::mt19937 gen(2);
  std::uniform_int_distribution<VertexId> pick(0, b.pointCount - 1);
  for (int k = 0; k < 200; ++k)
  {
    const VertexId a = pick(gen), c = pick(gen);
    if (a == c)
      continue;
    flipEdgeIntoMesh(
      mesh,
      index,
      a,
      c,
      [&](VertexId p, VertexId q) { return initial.count(std::minmax(p, q)) > 0; },
      [&](const FlipCandidate& move, bool)
      { replaceTets(mesh, index, move.oldTets, move.newTets); });
  }
  const auto after = edgesOf(mesh);
  for (const auto& e : initial)
    EXPECT_TRUE(after.count(e)) << e.first << "-" << e.second;
}

// On a lattice, the segment from a corner to the far end of a lattice line passes through the
// points between: no flip can make it an edge, and none is made.
TEST(DirectionalEdgeRecovery, RefusesASegmentThroughAVertex)
{
  Built b = delaunayOf(tetmesher::testing::gridPoints(4));
  TetMesh& mesh = b.mesh;
  VertexTetIndex index;
  index.rebuild(mesh);
  // Points (0,0,0) and (3,0,0): find them by coordinates.
  VertexId first = -1, last = -1;
  for (VertexId v = 0; v < b.pointCount; ++v)
  {
    const double* p = mesh.point(v);
    if (p[1] == 0 && p[2] == 0 && p[0] == 0)
      first = v;
    if (p[1] == 0 && p[2] == 0 && p[0] == 3)
      last = v;
  }
  ASSERT_GE(first, 0);
  ASSERT_GE(last, 0);
  const auto before = edgesOf(mesh);
  int moves = 0;
  EXPECT_FALSE(flipEdgeIntoMesh(
    mesh,
    index,
    first,
    last,
    [](VertexId, VertexId) { return false; },
    [&](const FlipCandidate& move, bool)
    {
      ++moves;
      replaceTets(mesh, index, move.oldTets, move.newTets);
    }));
  EXPECT_EQ(moves, 0);
  EXPECT_EQ(edgesOf(mesh), before);
}
