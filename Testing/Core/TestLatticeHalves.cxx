// The refinement's large rounds (lattice prefill, edge splitting) go in two halves of space on
// two threads (MeshHalves): the mesh must be the same on one thread and on two, and keep every
// invariant of the pipeline (exact boundary, volumes, orientation: checkMesh). The rounds'
// threshold is lowered so that small meshes (and ThreadSanitizer runs) exercise the halves.
#include "MeshChecks.h"
#include "SurfaceGenerators.h"
#include "VolumeMesher.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

using namespace tetmesher;
using namespace tetmesher::testing;

namespace
{

VolumeMeshResult meshWithThreads(const Surface& s, double h, const char* threads)
{
  setenv("TETMESHER_THREADS", threads, 1);
  VolumeMeshOptions options;
  options.refinement.halvesMinPoints = 1000;
  options.inputSizes.assign(static_cast<std::size_t>(s.pointCount()), h);
  VolumeMeshResult v =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  unsetenv("TETMESHER_THREADS");
  return v;
}

void expectSameOnOneAndTwoThreads(const Surface& s, double h)
{
  const VolumeMeshResult one = meshWithThreads(s, h, "1");
  ASSERT_TRUE(one.ok) << one.error;
  // The halves really ran, for the lattice and for the edge splitting.
  EXPECT_GT(one.refinementStats.latticeHalvesPoints, 1000);
  EXPECT_GT(one.refinementStats.splitHalvesPoints, 100);
  // And a large round's rest (next to the split) went into halves again.
  EXPECT_GT(one.refinementStats.latticeSecondSplits, 0);
  std::printf("%d lattice points by the halves, %d edge-splitting points, %zu tets\n",
    one.refinementStats.latticeHalvesPoints,
    one.refinementStats.splitHalvesPoints,
    one.tets.size() / 4);
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  EXPECT_EQ(checkMesh(s, asMesherResult(one, s.pointCount()), sign, 1), "");
  // Repeated: a race between the threads would show as a difference sooner or later.
  for (int run = 0; run < 2; ++run)
  {
    const VolumeMeshResult two = meshWithThreads(s, h, "2");
    ASSERT_TRUE(two.ok) << two.error;
    EXPECT_EQ(two.points, one.points);
    EXPECT_EQ(two.tets, one.tets);
    EXPECT_EQ(two.regionIds, one.regionIds);
    EXPECT_EQ(two.vertexSize, one.vertexSize);
  }
}

} // namespace

TEST(LatticeHalves, CubeIsTheSameOnOneAndTwoThreads)
{
  expectSameOnOneAndTwoThreads(cube(4), 0.035);
}

TEST(LatticeHalves, TorusIsTheSameOnOneAndTwoThreads)
{
  // Not convex: walks reach the hole's surface and are postponed.
  expectSameOnOneAndTwoThreads(torus(1.0, 0.4, 48, 24), 0.05);
}

TEST(LatticeHalves, FineSurfaceIsTheSameOnOneAndTwoThreads)
{
  // Triangles smaller than h: the size ceiling (BoundarySizeCeiling) is queried by both
  // halves of the lattice scan at once, and makes its per-cell face lists as it goes (published
  // atomically; its earlier cache of cell bounds was a data race under ThreadSanitizer).
  const Surface s = cube(32);
  const double h = 0.07;
  const VolumeMeshResult v = meshWithThreads(s, h, "1");
  ASSERT_TRUE(v.ok) << v.error;
  // The ceiling is at work: next to the triangles (edges 1/32) new points get sizes below h.
  int lowered = 0;
  for (std::size_t i = static_cast<std::size_t>(s.pointCount()); i < v.vertexSize.size(); ++i)
    lowered += v.vertexSize[i] < 0.8 * h;
  EXPECT_GT(lowered, 500);
  expectSameOnOneAndTwoThreads(s, h);
}
