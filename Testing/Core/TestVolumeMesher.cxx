// The whole pipeline (boundary mesh -> interior points -> optimisation): the boundary stays
// exact through every stage, sizes follow h, quality improves.
#include "MeshChecks.h"
#include "SurfaceGenerators.h"
#include "TetQuality.h"
#include "VolumeMesher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace tetmesher;
using namespace tetmesher::testing;

namespace
{

tetmesher::MesherResult asMesherResult(const VolumeMeshResult& v, std::int32_t inputPoints)
{
  MesherResult r;
  r.ok = v.ok;
  r.error = v.error;
  r.points = v.points;
  r.tets = v.tets;
  r.regionIds = v.regionIds;
  r.boundaryFaceTet = v.boundaryFaceTet;
  r.regionCount = v.regionCount;
  r.steinerPoints = static_cast<int>(v.points.size() / 3) - inputPoints;
  return r;
}

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
  EXPECT_GE(minQuality(v, v.tets), minQuality(v, v.tetsBeforeOptimization));
  std::printf("cube h=%.2f: %zu tets, %d interior points, Q min %.3f -> %.3f\n",
    h,
    v.tets.size() / 4,
    v.interiorPoints,
    minQuality(v, v.tetsBeforeOptimization),
    minQuality(v, v.tets));
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
