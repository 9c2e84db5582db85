// The whole pipeline (boundary mesh -> interior points -> optimisation): the boundary stays
// exact through every stage, sizes follow h, quality improves.
#include "MemoryBudget.h"
#include "MeshChecks.h"
#include "SurfaceGenerators.h"
#include "TetQuality.h"
#include "VolumeMesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace tetmesher;
using namespace tetmesher::testing;

namespace
{

double minQuality(const VolumeMeshResult& v, const std::vector<std::int32_t>& tets)
{
  double q = 1;
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
  {
    const double* p[4];
    for (int i = 0; i < 4; ++i)
      p[i] = &v.points[3 * static_cast<std::size_t>(tets[4 * t + static_cast<std::size_t>(i)])];
    // TetMesh orientation is the reverse of VTK's: swap two vertices to measure.
    q = std::min(q, measureTet(p[1], p[0], p[2], p[3]).quality);
  }
  return q;
}
} // namespace

TEST(VolumeMesher, CubeWithConstantSizeKeepsTheBoundaryAndFollowsH)
{
  Surface s = cube(4); // unit cube, faces split 4x4
  VolumeMeshOptions options;
  const double h = 0.15;
  options.inputSizes.assign(static_cast<std::size_t>(s.pointCount()), h);
  VolumeMeshResult v =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  ASSERT_TRUE(v.ok) << v.error;
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  EXPECT_EQ(checkMesh(s, asMesherResult(v, s.pointCount()), sign, 1), "");
  EXPECT_GT(v.interiorPoints, 0);
  ASSERT_EQ(v.vertexSize.size(), v.points.size() / 3);
  // Optimisation never makes the worst element worse.
  const double before =
    *std::min_element(v.qualityBeforeOptimization.begin(), v.qualityBeforeOptimization.end());
  EXPECT_GE(minQuality(v, v.tets), before);
  std::printf("cube h=%.2f: %zu tets, %d interior points, Q min %.3f -> %.3f\n",
    h,
    v.tets.size() / 4,
    v.interiorPoints,
    before,
    minQuality(v, v.tets));

  // The Q values before optimisation are those of the mesh the refinement left: the same run
  // without optimisation ends with that mesh (the smoothing moves points, so its tets measured
  // on the optimised points would give other values).
  options.optimize = false;
  const VolumeMeshResult plain =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  ASSERT_TRUE(plain.ok) << plain.error;
  std::vector<double> expected;
  for (std::size_t t = 0; t < plain.tets.size() / 4; ++t)
  {
    const double* p[4];
    for (int i = 0; i < 4; ++i)
      p[i] =
        &plain
           .points[3 * static_cast<std::size_t>(plain.tets[4 * t + static_cast<std::size_t>(i)])];
    expected.push_back(measureTet(p[1], p[0], p[2], p[3]).quality);
  }
  std::vector<double> got = v.qualityBeforeOptimization;
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, expected);
  EXPECT_EQ(static_cast<int>(got.size()), v.optimizationStats.tetsBefore);
  std::vector<double> plainBefore = plain.qualityBeforeOptimization;
  std::sort(plainBefore.begin(), plainBefore.end());
  EXPECT_EQ(plainBefore, expected);
}

// TetGen's region list with a volume bound per region, as a max size per region point: the
// ball inside nested spheres is meshed to its bound (away from its surface, where the size
// floor grades up to the triangles), the shell around it only near their interface; the
// boundary stays exact.
TEST(VolumeMesher, RegionMaxSizeBoundsTheSizeInItsRegion)
{
  Surface s = icosphere(3, 1.0);
  const std::int32_t outer = s.triangleCount();
  s.append(icosphere(2, 0.5));
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 0);
  std::fill(sign.begin(), sign.begin() + outer, 1);
  const double cap = 0.05;
  struct Stats
  {
    int ballPoints = 0, shellPoints = 0;
    double coreShort = 0; // share of the edges within 0.2 of the centre no longer than 1.42 cap
  };
  auto run = [&](bool capped)
  {
    VolumeMeshOptions options;
    options.boundary.regionPoints = { 0, 0, 0.01, 1 };
    options.boundary.regionMaxSizes = { capped ? cap : 0.0 };
    const VolumeMeshResult v =
      meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
    EXPECT_TRUE(v.ok) << v.error;
    EXPECT_EQ(checkMesh(s, asMesherResult(v, s.pointCount()), sign, 2), "");
    Stats stats;
    if (!v.ok || v.regionAttribute.size() != 2)
      return stats;
    std::vector<int> where(v.points.size() / 3, -1); // region of a new point
    std::size_t edges = 0, shortEdges = 0;
    for (std::size_t t = 0; t < v.tets.size() / 4; ++t)
    {
      const bool ball = v.regionAttribute[static_cast<std::size_t>(v.regionIds[t])] == 1;
      for (int i = 0; i < 4; ++i)
      {
        const std::int32_t a = v.tets[4 * t + static_cast<std::size_t>(i)];
        if (a >= s.pointCount())
          where[static_cast<std::size_t>(a)] = ball ? 1 : 0;
        for (int j = i + 1; j < 4 && ball; ++j)
        {
          const std::int32_t b = v.tets[4 * t + static_cast<std::size_t>(j)];
          const double* p = &v.points[3 * static_cast<std::size_t>(a)];
          const double* q = &v.points[3 * static_cast<std::size_t>(b)];
          if (std::hypot(p[0] + q[0], p[1] + q[1], p[2] + q[2]) > 0.4)
            continue; // the midpoint is farther than 0.2 from the centre
          ++edges;
          shortEdges += std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) <= 1.42 * cap;
        }
      }
    }
    for (int w : where)
      (w == 1 ? stats.ballPoints : stats.shellPoints) += w >= 0;
    stats.coreShort = edges ? static_cast<double>(shortEdges) / static_cast<double>(edges) : 0;
    std::printf("region cap %s: %d points in the ball, %d in the shell, %.1f%% of the core's "
                "edges <= 1.42 cap\n",
      capped ? "on" : "off",
      stats.ballPoints,
      stats.shellPoints,
      100 * stats.coreShort);
    return stats;
  };
  const Stats free = run(false), capped = run(true);
  EXPECT_GE(capped.coreShort, 0.9);
  EXPECT_LT(free.coreShort, 0.5);
  EXPECT_GT(capped.ballPoints, 4 * free.ballPoints);
  // The shell grades up from the ball's size at their interface (its vertices take the
  // smaller bound), not the ball's size throughout: that would be 50x its points.
  EXPECT_LT(capped.shellPoints, 4 * free.shellPoints);
}

// The whole pipeline on a surface with unused points on it (left out of the mesh) and inside
// it (a vertex of the mesh): the boundary exact, the points on the surface in no tet.
TEST(VolumeMesher, UnusedPointsOnTheSurfaceStayOutOfTheMesh)
{
  Surface s = cube(3);
  const std::int32_t firstOnSurface = s.pointCount();
  s.addPoint(0.1, 0.2, 1);
  s.addPoint(0, 0.5, 0.5);
  s.addPoint(1.0 / 3, 0, 0.2);
  const std::int32_t inside = s.addPoint(0.5, 0.5, 0.5);
  VolumeMeshOptions options;
  options.inputSizes.assign(static_cast<std::size_t>(s.pointCount()), 0.2);
  const VolumeMeshResult v =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  ASSERT_TRUE(v.ok) << v.error;
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  EXPECT_EQ(checkMesh(s, asMesherResult(v, s.pointCount()), sign, 1), "");
  std::vector<char> used(v.points.size() / 3, 0);
  for (std::int32_t id : v.tets)
    used[static_cast<std::size_t>(id)] = 1;
  for (std::int32_t id = firstOnSurface; id < inside; ++id)
    EXPECT_FALSE(used[static_cast<std::size_t>(id)]) << "point " << id;
  EXPECT_TRUE(used[static_cast<std::size_t>(inside)]);
  EXPECT_GT(v.interiorPoints, 0);
}

// Issue 8's targets on good surface triangles, with the default options: Q min >= 0.3, share
// of Q < 0.3 under 0.1%, min dihedral >= 20 degrees; at h matching the surface, at h/2, much
// finer than the surface (the size floor's regime: cube(7) at h = 1/35, edges 5 h) and much
// coarser (the size ceiling's: edges h/3.5 to h/4).
TEST(VolumeMesher, GoodSurfacesReachTheQualityTargets)
{
  struct Case
  {
    const char* name;
    Surface surface;
    double h;
  };
  const double ico = 2 * std::sin(0.5 * 1.1071487177940904) / 8; // icosphere(3)'s edge, ~0.138
  const Case cases[] = {
    { "cube(7) h=1/7", cube(7), 1.0 / 7 },
    { "cube(7) h=1/14", cube(7), 1.0 / 14 },
    { "cube(7) h=1/35", cube(7), 1.0 / 35 },
    { "icosphere(3) h=edge/2", icosphere(3), ico / 2 },
    { "torus h=edge/2", torus(1.0, 0.4, 32, 16), 0.1 },
    // h far above the surface's edges: the ceiling grades the sizes up from the faces.
    { "cube(7) h=0.5", cube(7), 0.5 },
    { "icosphere(3) h=4 edges", icosphere(3), 4 * ico },
    { "torus h=0.5", torus(1.0, 0.4, 32, 16), 0.5 },
  };
  for (const Case& c : cases)
  {
    VolumeMeshOptions options;
    options.inputSizes.assign(static_cast<std::size_t>(c.surface.pointCount()), c.h);
    VolumeMeshResult v = meshVolume(c.surface.points.data(),
      c.surface.pointCount(),
      c.surface.triangles.data(),
      c.surface.triangleCount(),
      options);
    ASSERT_TRUE(v.ok) << c.name << ": " << v.error;
    std::vector<int> sign(static_cast<std::size_t>(c.surface.triangleCount()), 1);
    EXPECT_EQ(checkMesh(c.surface, asMesherResult(v, c.surface.pointCount()), sign, 1), "")
      << c.name;
    double qMin = 1, dMin = 180;
    std::size_t below = 0;
    const std::size_t tets = v.tets.size() / 4;
    for (std::size_t t = 0; t < tets; ++t)
    {
      const double* p[4];
      for (int i = 0; i < 4; ++i)
        p[i] = &v.points[3 * static_cast<std::size_t>(v.tets[4 * t + static_cast<std::size_t>(i)])];
      const TetShape shape = measureTet(p[1], p[0], p[2], p[3]);
      qMin = std::min(qMin, shape.quality);
      dMin = std::min(dMin, shape.minDihedral);
      below += shape.quality < 0.3;
    }
    std::printf("[%s] %zu tets, Q min %.3f, min dihedral %.1f deg, %zu below Q 0.3\n",
      c.name,
      tets,
      qMin,
      dMin,
      below);
    EXPECT_GE(qMin, 0.3) << c.name;
    EXPECT_GE(dMin, 20.0) << c.name;
    EXPECT_LT(double(below), 1e-3 * double(tets)) << c.name;
  }
}

TEST(VolumeMesher, TwoRegionsStayApartAndBoundaryOnlyIsTheBoundaryMesh)
{
  std::vector<char> shared;
  Surface s = twoCubes(shared);
  VolumeMeshOptions options;
  VolumeMeshResult v =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  ASSERT_TRUE(v.ok) << v.error;
  EXPECT_EQ(v.regionCount, 2);

  options.refine = false;
  options.optimize = false;
  VolumeMeshResult boundaryOnly =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  ASSERT_TRUE(boundaryOnly.ok) << boundaryOnly.error;
  MesherResult direct =
    meshSurface(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount());
  EXPECT_EQ(boundaryOnly.tets, direct.tets);
  EXPECT_EQ(boundaryOnly.points, direct.points);
}

TEST(VolumeMesher, Deterministic)
{
  Surface s = icosphere(2);
  VolumeMeshOptions options;
  VolumeMeshResult a =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  VolumeMeshResult b =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  ASSERT_TRUE(a.ok) << a.error;
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.tets, b.tets);
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  EXPECT_EQ(checkMesh(s, asMesherResult(a, s.pointCount()), sign, 1), "");
}

TEST(VolumeMesher, OptimisationWorkBoundStopsAtTheSameMove)
{
  // The optimiser's bound counts its work, not wall time: stopped at its first poll it stops
  // at the same move on every run, and the mesh is valid, exact and complete.
  Surface s = icosphere(2);
  VolumeMeshOptions bounded;
  bounded.optimizationPolls = 0;
  bounded.optimizationPollsPerTet = 0;
  bounded.refinement.size.scale = 0.3;
  VolumeMeshResult a =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), bounded);
  VolumeMeshResult b =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), bounded);
  ASSERT_TRUE(a.ok) << a.error;
  EXPECT_TRUE(a.optimizationStoppedByBound);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.tets, b.tets);
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  EXPECT_EQ(checkMesh(s, asMesherResult(a, s.pointCount()), sign, 1), "");
  // Unbounded (and by default) this surface finishes well within the bound.
  VolumeMeshOptions unbounded = bounded;
  unbounded.optimizationPolls = -1;
  VolumeMeshResult c =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), unbounded);
  ASSERT_TRUE(c.ok) << c.error;
  EXPECT_FALSE(c.optimizationStoppedByBound);
  EXPECT_NE(c.tets, a.tets); // the bound did stop it early
}

namespace
{
Surface transformed(const Surface& s, double scale, double shift)
{
  Surface t = s;
  for (double& c : t.points)
    c = c * scale + shift;
  return t;
}

// The full pipeline on `s` moved to another magnitude: every invariant of the contract holds
// (exact boundary, exact volume, positive orientation), and the mesh has about as many tets
// and a worst element about as good as at unit scale. Only about: a decimal scale rounds the
// coordinates differently, and the mesh changes as it does for any scale (1.1, 3, 10 give
// +-5% tets and Q min 0.23-0.31 on the torus), which is not a matter of magnitude.
void expectMeshesLikeUnitScale(const Surface& s,
  const VolumeMeshResult& reference,
  double scale,
  double shift)
{
  Surface t = transformed(s, scale, shift);
  VolumeMeshResult v =
    meshVolume(t.points.data(), t.pointCount(), t.triangles.data(), t.triangleCount(), {});
  ASSERT_TRUE(v.ok) << "scale " << scale << " shift " << shift << ": " << v.error;
  std::vector<int> sign(static_cast<std::size_t>(t.triangleCount()), 1);
  EXPECT_EQ(checkMesh(t, asMesherResult(v, t.pointCount()), sign, 1), "")
    << "scale " << scale << " shift " << shift;
  const double ratio =
    static_cast<double>(v.tets.size()) / static_cast<double>(reference.tets.size());
  EXPECT_GT(ratio, 0.85) << "scale " << scale << " shift " << shift;
  EXPECT_LT(ratio, 1.15) << "scale " << scale << " shift " << shift;
  EXPECT_GE(minQuality(v, v.tets), 0.7 * minQuality(reference, reference.tets))
    << "scale " << scale << " shift " << shift;
}
} // namespace

// No absolute tolerance anywhere: a surface scaled by a power of two gives exactly the same
// mesh (the same tets, every point scaled), from 2^-40 (about 1e-12) to 2^40 (about 1e12);
// decimal scales 1e-12 and 1e12, and a translation to 1e12, give valid meshes of the same
// size and quality.
TEST(VolumeMesher, CoordinatesFrom1eMinus12To1e12)
{
  for (const Surface& s : { torus(1.0, 0.35, 24, 12), slottedRing(12, 4, 0.4, 0.6, 1.0, 0.3) })
  {
    VolumeMeshResult reference =
      meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), {});
    ASSERT_TRUE(reference.ok) << reference.error;
    for (int exponent : { -40, 40 })
    {
      const double scale = std::ldexp(1.0, exponent);
      Surface t = transformed(s, scale, 0);
      VolumeMeshResult v =
        meshVolume(t.points.data(), t.pointCount(), t.triangles.data(), t.triangleCount(), {});
      ASSERT_TRUE(v.ok) << "2^" << exponent << ": " << v.error;
      EXPECT_EQ(v.tets, reference.tets) << "2^" << exponent;
      ASSERT_EQ(v.points.size(), reference.points.size()) << "2^" << exponent;
      std::size_t differing = 0;
      for (std::size_t i = 0; i < v.points.size(); ++i)
        differing += v.points[i] != reference.points[i] * scale;
      EXPECT_EQ(differing, 0u) << "2^" << exponent;
    }
    expectMeshesLikeUnitScale(s, reference, 1e-12, 0);
    expectMeshesLikeUnitScale(s, reference, 1e12, 0);
    expectMeshesLikeUnitScale(s, reference, 1e9, 1e12);
  }
}

// A size field whose mesh would not fit is refused before refinement inserts anything, with
// the estimate and the limit in the message.
TEST(VolumeMesher, SizeFieldBeyondTheMemoryLimitIsRefused)
{
  EXPECT_EQ(checkMemoryBudget(1e5, 1e9), "");
  EXPECT_EQ(checkMemoryBudget(1e5, 0), ""); // no limit
  const std::string tooMuch = checkMemoryBudget(1e6, 1e9);
  EXPECT_NE(tooMuch.find("about 1e+06 interior points"), std::string::npos) << tooMuch;
  EXPECT_NE(tooMuch.find("2 GB of memory"), std::string::npos) << tooMuch;
  EXPECT_NE(tooMuch.find("more than the memory limit of 1 GB"), std::string::npos) << tooMuch;
  // 2^29 tets is the index limit, with or without a memory limit.
  EXPECT_NE(checkMemoryBudget(1e8, 0).find("tetrahedra a mesh can have"), std::string::npos);
  EXPECT_GT(availableMemoryBytes(), 0.0);

  Surface s = cube(4);
  VolumeMeshOptions options;
  const double h = 0.01; // about sqrt(2)/h^3 = 1.4e6 points in the unit cube: 2.8 GB
  options.inputSizes.assign(static_cast<std::size_t>(s.pointCount()), h);
  options.refinement.memoryLimitBytes = 1e9;
  VolumeMeshResult v =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  EXPECT_FALSE(v.ok);
  EXPECT_NE(v.error.find("more than the memory limit of 1 GB"), std::string::npos) << v.error;
  EXPECT_EQ(v.refinementStats.insertedPoints, 0);
  EXPECT_TRUE(v.tets.empty());
  EXPECT_NEAR(v.refinementStats.estimatedPoints, std::sqrt(2.0) / (h * h * h), 0.01e6);
}

// The boundary mesh is estimated from the point count before the Delaunay stage.
TEST(VolumeMesher, SurfaceBeyondTheMemoryLimitIsRefused)
{
  EXPECT_EQ(checkBoundaryMemoryBudget(1e6, 1e10), "");
  const std::string tooMuch = checkBoundaryMemoryBudget(1e6, 1e9);
  EXPECT_NE(tooMuch.find("the surface has 1e+06 points"), std::string::npos) << tooMuch;
  EXPECT_NE(tooMuch.find("2.5 GB of memory, more than the memory limit of 1 GB"), std::string::npos)
    << tooMuch;
  EXPECT_NE(
    checkBoundaryMemoryBudget(1e8, 0).find("tetrahedra a mesh can have"), std::string::npos);

  Surface s = icosphere(3); // 642 points: 1.6 MB estimated
  MesherOptions options;
  options.memoryLimitBytes = 1e6;
  MesherResult r =
    meshSurface(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("the surface has 642 points"), std::string::npos) << r.error;
  EXPECT_TRUE(r.tets.empty());
  options.memoryLimitBytes = 2e6;
  r = meshSurface(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  EXPECT_TRUE(r.ok) << r.error;
}

// A stage stops once a pass changed tets but neither raised the minimum nor left fewer tets
// below the target, rather than running its other passes on tets that the surface's slot
// corners bound (a ring with 24 deep slots: 5 passes of 6). The minima still
// never fall, and the boundary is kept.
TEST(VolumeMesher, OptimiserEndsAStageThatNoLongerGains)
{
  Surface s = slottedRing(24, 3, 1.0, 1.5, 1.8, 0.6);
  const VolumeMeshOptions options;
  const VolumeMeshResult v =
    meshVolume(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), options);
  ASSERT_TRUE(v.ok) << v.error;
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  EXPECT_EQ(checkMesh(s, asMesherResult(v, s.pointCount()), sign, 1), "");
  const OptimizationResult& r = v.optimizationStats;
  std::printf("slotted ring: %d passes, %d stage(s) ended without gain, Q min %.4f -> %.4f, "
              "dihedral min %.2f -> %.2f\n",
    r.passesRun,
    r.stagesEndedWithoutGain,
    r.minQualityBefore,
    r.minQualityAfter,
    r.minDihedralBefore,
    r.minDihedralAfter);
  EXPECT_GE(r.stagesEndedWithoutGain, 1);
  EXPECT_LT(r.passesRun, 2 * options.optimization.passes);
  EXPECT_GE(r.minQualityAfter, r.minQualityBefore);
  EXPECT_GE(r.minDihedralAfter, r.minDihedralBefore);
}

// Points given inside (TetGen's -i list) are vertices with output ids n, n+1, ... right after
// the n input points, bit-identical, before the boundary mesh's Steiner points, never moved by the
// optimiser; the boundary stays exact. Points that cannot be vertices strictly inside are errors
// naming them.
namespace
{

// "" when the given points (3 doubles each) are output points n, n+1, ... in order, each a
// vertex of some tet and bit for bit where it was given; else the first problem.
std::string givenPointsProblem(const VolumeMeshResult& v,
  std::int32_t n,
  const std::vector<double>& given)
{
  std::vector<char> used(v.points.size() / 3, 0);
  for (std::int32_t id : v.tets)
    used[static_cast<std::size_t>(id)] = 1;
  for (std::size_t i = 0; i < given.size() / 3; ++i)
  {
    const std::size_t id = static_cast<std::size_t>(n) + i;
    if (id >= used.size() || !used[id])
      return "given point " + std::to_string(i) + " is not a vertex";
    for (std::size_t k = 0; k < 3; ++k)
      if (v.points[3 * id + k] != given[3 * i + k])
        return "given point " + std::to_string(i) + " moved";
  }
  return "";
}

} // namespace

TEST(VolumeMesher, GivenInteriorPointsAreVerticesRightAfterTheInputPoints)
{
  const Surface s = twistedTower(8, 6, 0.35, 0.25); // Schonhardt bands: Steiner points
  const std::int32_t n = s.pointCount();
  const std::vector<double> given = { 0.01, 0.013, 0.4, -0.05, 0.02, 0.65 };
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  for (const bool full : { false, true })
  {
    VolumeMeshOptions options;
    options.refine = full;
    options.optimize = full;
    options.inputSizes.assign(static_cast<std::size_t>(n), 0.1);
    options.interiorPoints = given;
    const VolumeMeshResult v =
      meshVolume(s.points.data(), n, s.triangles.data(), s.triangleCount(), options);
    ASSERT_TRUE(v.ok) << v.error;
    EXPECT_GT(v.steinerPoints, 0) << "the tower needs Steiner points";
    EXPECT_EQ(checkMesh(s, asMesherResult(v, n), sign, 1), "") << "full " << full;
    std::vector<char> used(v.points.size() / 3, 0);
    for (std::int32_t id : v.tets)
      used[static_cast<std::size_t>(id)] = 1;
    EXPECT_EQ(givenPointsProblem(v, n, given), "") << "full " << full;
    // Every Steiner point (after the given ones) is a vertex too.
    for (std::size_t id = static_cast<std::size_t>(n) + 2;
         id < static_cast<std::size_t>(n) + 2 + static_cast<std::size_t>(v.steinerPoints);
         ++id)
      EXPECT_TRUE(used[id]) << "Steiner point " << id;
    // Refinement adds points around them (h = 0.1 in a tower of radius 1, height 1.5).
    EXPECT_EQ(v.interiorPoints > 2, full) << v.interiorPoints;
    EXPECT_EQ(v.vertexSize.size(), full ? v.points.size() / 3 : 0);
  }

  // Errors, each naming the point: outside, on a face, on an edge, at an input point, twice.
  const Surface c = cube(2); // unit cube, faces split 2x2
  const struct
  {
    std::vector<double> points;
    const char* message;
  } bad[] = {
    { { 0.5, 0.5, 0.5, 2, 0.5, 0.5 },
      "interior point 1 (2, 0.5, 0.5) is outside the meshed domain" },
    { { 0.25, 0.3, 0 }, "interior point 0 (0.25, 0.3, 0) lies on the surface" },
    { { 0.3, 0, 0 }, "interior point 0 (0.3, 0, 0) lies on the surface" },
    { { 0.5, 0.5, 0 }, "interior point 0 (0.5, 0.5, 0) coincides with input point" },
    { { 0.2, 0.3, 0.4, 0.2, 0.3, 0.4 },
      "interior point 1 (0.2, 0.3, 0.4) coincides with interior point 0" },
    { { 0.2, 0.3, std::nan("") }, "interior point 0 has a non-finite coordinate" },
  };
  for (const auto& b : bad)
    for (const bool refine : { false, true })
    {
      VolumeMeshOptions options;
      options.refine = refine;
      options.interiorPoints = b.points;
      const VolumeMeshResult v =
        meshVolume(c.points.data(), c.pointCount(), c.triangles.data(), c.triangleCount(), options);
      EXPECT_FALSE(v.ok);
      EXPECT_NE(v.error.find(b.message), std::string::npos) << v.error;
      EXPECT_TRUE(v.tets.empty());
    }
}

TEST(VolumeMesher, GivenPointsAcrossTheHoleOfATorus)
{
  // Each point on the other side of the hole from the one before: the walk from the last
  // point's tet reaches the boundary every time, so each point is found from a tet near it
  // (GivenPoints.cxx's WalkSeeds) or by the search of every tet. All are vertices, in order,
  // exactly where given; a point in the hole is named as outside.
  const Surface s = torus(1.0, 0.4, 24, 12);
  const std::int32_t n = s.pointCount();
  std::vector<double> given;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < 200; ++i)
  {
    // Angles that alternate across the hole; radii and heights inside the tube.
    const double u = 2 * pi * (0.37 * i + (i % 2 ? 0.5 : 0.0));
    const double r = 1.0 + 0.25 * std::cos(1.7 * i), z = 0.25 * std::sin(2.3 * i);
    given.insert(given.end(), { r * std::cos(u), r * std::sin(u), z });
  }
  std::vector<int> sign(static_cast<std::size_t>(s.triangleCount()), 1);
  VolumeMeshOptions options;
  options.refine = false;
  options.optimize = false;
  options.interiorPoints = given;
  const VolumeMeshResult v =
    meshVolume(s.points.data(), n, s.triangles.data(), s.triangleCount(), options);
  ASSERT_TRUE(v.ok) << v.error;
  EXPECT_EQ(checkMesh(s, asMesherResult(v, n), sign, 1), "");
  EXPECT_EQ(givenPointsProblem(v, n, given), "");
  // The same points, then one in the hole (the walk and the seeds both fail; so does the
  // search of every tet).
  options.interiorPoints.insert(options.interiorPoints.end(), { 0.05, 0.02, 0.0 });
  const VolumeMeshResult hole =
    meshVolume(s.points.data(), n, s.triangles.data(), s.triangleCount(), options);
  EXPECT_FALSE(hole.ok);
  EXPECT_NE(hole.error.find("interior point 200 (0.05, 0.02, 0) is outside the meshed domain"),
    std::string::npos)
    << hole.error;
}
