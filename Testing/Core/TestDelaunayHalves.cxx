// The Delaunay kernel's partitioned insertion (DelaunayOptions::partitioned): large BRIO rounds
// inserted in two halves of space, on two threads. The triangulation must be the one a single
// insertion sequence gives (the symbolic perturbation makes it unique), exactly valid on
// degenerate input, and the arrays must not depend on the number of threads.
#include "Delaunay.h"
#include "PointSets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

using namespace tetmesher;
using namespace tetmesher::testing;

namespace
{

// Large enough that the last BRIO round (7/8 of the points) is split in halves.
constexpr int kPoints = 60000;

// The live tets as sorted vertex quadruples, sorted: the triangulation without its numbering.
std::vector<std::array<VertexId, 4>> tetSet(const TetMesh& mesh)
{
  std::vector<std::array<VertexId, 4>> tets;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (!mesh.isDeleted(t))
    {
      std::array<VertexId, 4> q{
        mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3)
      };
      std::sort(q.begin(), q.end());
      tets.push_back(q);
    }
  std::sort(tets.begin(), tets.end());
  return tets;
}

DelaunayResult build(TetMesh& mesh, bool partitioned, int threads = 0)
{
  DelaunayOptions options;
  options.partitioned = partitioned;
  options.threads = threads;
  options.validate = true; // exact: orientation, adjacency, empty spheres, every point present
  return buildDelaunay(mesh, options);
}

void expectSameTriangulation(const TetMesh& input)
{
  TetMesh halves = input, sequence = input;
  const DelaunayResult a = build(halves, true);
  const DelaunayResult b = build(sequence, false);
  ASSERT_TRUE(a.ok) << a.error;
  ASSERT_TRUE(b.ok) << b.error;
  // Different numbering: the halves really ran (else this test would compare a build with
  // itself).
  EXPECT_NE(halves.tets, sequence.tets);
  EXPECT_EQ(tetSet(halves), tetSet(sequence));
}

} // namespace

TEST(DelaunayHalves, UniformPointsGiveTheSameTriangulationAsOneSequence)
{
  expectSameTriangulation(randomPoints(kPoints, 11));
}

TEST(DelaunayHalves, CosphericalPointsGiveTheSameTriangulationAsOneSequence)
{
  expectSameTriangulation(pointsOnUnitSphere(kPoints, 12));
}

TEST(DelaunayHalves, GridGivesTheSameTriangulationAsOneSequence)
{
  expectSameTriangulation(gridPoints(40));
}

TEST(DelaunayHalves, ClusteredPointsGiveTheSameTriangulationAsOneSequence)
{
  // Dense clusters in a sparse cloud: the halves' split lands inside a cluster.
  TetMesh mesh = randomPoints(kPoints / 4, 13);
  std::mt19937_64 gen(14);
  std::normal_distribution<double> g;
  for (int c = 0; c < 6; ++c)
  {
    const double cx = 0.5 + 0.3 * g(gen), cy = 0.5 + 0.3 * g(gen), cz = 0.5 + 0.3 * g(gen);
    for (int i = 0; i < kPoints / 8; ++i)
      mesh.addVertex(cx + 1e-3 * g(gen), cy + 1e-3 * g(gen), cz + 1e-3 * g(gen));
  }
  expectSameTriangulation(mesh);
}

TEST(DelaunayHalves, ThreadCountDoesNotChangeTheArrays)
{
  const TetMesh input = randomPoints(kPoints, 15);
  TetMesh one = input;
  ASSERT_TRUE(build(one, true, 1).ok);
  // Repeated: a race between the two threads would show as a difference sooner or later.
  for (int run = 0; run < 3; ++run)
  {
    TetMesh two = input;
    ASSERT_TRUE(build(two, true, 2).ok);
    EXPECT_EQ(two.tets, one.tets);
    EXPECT_EQ(two.neighbors, one.neighbors);
    EXPECT_EQ(two.freeTets, one.freeTets);
  }
}

TEST(DelaunayHalves, DuplicatesAreReportedOnceEach)
{
  TetMesh mesh = randomPoints(kPoints, 16);
  std::mt19937_64 gen(17);
  const VertexId original = mesh.vertexCount();
  for (int i = 0; i < kPoints / 3; ++i)
  {
    const double* p = mesh.point(static_cast<VertexId>(gen() % original));
    mesh.addVertex(p[0], p[1], p[2]);
  }
  const VertexId n = mesh.vertexCount();
  const DelaunayResult r = build(mesh, true);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.duplicates.size(), r.duplicateOf.size());
  // Exactly one vertex of each set of equal points is in the mesh; the others are reported,
  // each as a duplicate of the one kept.
  std::map<std::array<double, 3>, int> copies;
  for (VertexId v = 0; v < n; ++v)
    ++copies[{ mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2] }];
  EXPECT_EQ(r.duplicates.size(), static_cast<std::size_t>(n) - copies.size());
  std::set<VertexId> used;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (!mesh.isDeleted(t))
      for (int k = 0; k < 4; ++k)
        used.insert(mesh.vertex(t, k));
  EXPECT_EQ(used.size(), copies.size() + 8); // and the 8 box corners
  for (std::size_t i = 0; i < r.duplicates.size(); ++i)
  {
    EXPECT_EQ(used.count(r.duplicates[i]), 0u);
    EXPECT_EQ(used.count(r.duplicateOf[i]), 1u);
    const double* a = mesh.point(r.duplicates[i]);
    const double* b = mesh.point(r.duplicateOf[i]);
    EXPECT_TRUE(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
  }
}
