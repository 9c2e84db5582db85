// The quality optimiser's passes with many bad tets work in two halves of space on two threads,
// then work what needed both halves in one sequence: the mesh must be the same on one thread and
// on two (also when the callers' work bound stops the optimiser in the middle of a pass), keep
// every invariant of the pipeline (exact boundary, volumes, orientation: checkMesh), and keep
// the optimiser's promise that the minimum Q and dihedral angle never decrease. The threshold
// is lowered so that small meshes (and ThreadSanitizer runs) exercise the halves.
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

VolumeMeshResult meshWithThreads(const Surface& s,
  double h,
  const char* threads,
  std::int64_t polls)
{
  setenv("TETMESHER_THREADS", threads, 1);
  VolumeMeshOptions options;
  options.optimization.halvesMinBadTets = 32;
  options.optimizationPolls = polls;
  if (polls >= 0)
    options.optimizationPollsPerTet = 0;
  options.inputSizes.assign(static_cast<std::size_t>(s.pointCount()), h);
  VolumeMeshResult v =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  unsetenv("TETMESHER_THREADS");
  return v;
}

void expectSameOnOneAndTwoThreads(const Surface& s, double h, std::int64_t polls = -1)
{
  const VolumeMeshResult one = meshWithThreads(s, h, "1", polls);
  ASSERT_TRUE(one.ok) << one.error;
  const OptimizationResult& o = one.optimizationStats;
  // The halves really ran.
  EXPECT_GT(o.passesInHalves, 0);
  std::printf("%d of %d passes in halves, %d tets, %.1f%% below the target, Q min %.4f -> %.4f, "
              "dihedral min %.2f -> "
              "%.2f, %d smoothings, %d flips 3-2%s\n",
    o.passesInHalves,
    o.passesRun,
    o.tetsAfter,
    100 * o.shareBelowTargetBefore,
    o.minQualityBefore,
    o.minQualityAfter,
    o.minDihedralBefore,
    o.minDihedralAfter,
    o.smoothedVertices,
    o.flips32,
    one.optimizationStoppedByBound ? ", stopped by the work bound" : "");
  EXPECT_GE(o.minQualityAfter, o.minQualityBefore);
  EXPECT_GE(o.minDihedralAfter, o.minDihedralBefore);
  if (polls >= 0)
  {
    EXPECT_TRUE(one.optimizationStoppedByBound);
  }
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  EXPECT_EQ(checkMesh(s, asMesherResult(one, s.pointCount()), sign, 1), "");
  // Repeated: a race between the threads would show as a difference sooner or later.
  for (int run = 0; run < 2; ++run)
  {
    const VolumeMeshResult two = meshWithThreads(s, h, "2", polls);
    ASSERT_TRUE(two.ok) << two.error;
    EXPECT_EQ(two.points, one.points);
    EXPECT_EQ(two.tets, one.tets);
    EXPECT_EQ(two.regionIds, one.regionIds);
    EXPECT_EQ(two.vertexSize, one.vertexSize);
    EXPECT_EQ(two.optimizationStats.passesInHalves, o.passesInHalves);
  }
}

} // namespace

TEST(OptimizerHalves, TorusIsTheSameOnOneAndTwoThreads)
{
  // A good surface: the queue alone works on the few bad tets. Over 65536 tets: the scans of
  // every tet go in halves too.
  expectSameOnOneAndTwoThreads(torus(1.0, 0.4, 48, 24), 0.07);
}

TEST(OptimizerHalves, PoorSphereIsTheSameOnOneAndTwoThreads)
{
  // Needle triangles at the poles: many tets stay bad, so each pass sweeps their vertices
  // first.
  expectSameOnOneAndTwoThreads(uvSphere(96, 6), 0.1);
}

TEST(OptimizerHalves, WorkBoundStopsAtTheSameMoveOnOneAndTwoThreads)
{
  // The callers' work bound ends the optimiser in the middle of a pass, while the second half
  // runs: it must stop it at the same point on one thread and on two.
  expectSameOnOneAndTwoThreads(uvSphere(96, 6), 0.1, 6);
}
