// The cone refill of a cavity (CavityCone.h) on Delaunay meshes of random points, checked
// exactly (orientation, adjacency, vertices, volume), and its use by boundary recovery on a
// flat face folded at the scale of rounding (netgen's hinge.stl in miniature).
#include "CavityCone.h"
#include "ConstraintRecovery.h"
#include "Delaunay.h"
#include "MeshChecks.h"
#include "MeshTopology.h"
#include "MeshValidation.h"
#include "Mesher.h"
#include "RecoveryGeometry.h"
#include "SurfaceGenerators.h"
#include "SurfaceInput.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace tetmesher;
using namespace tetmesher::testing;

namespace
{

TetMesh randomDelaunay(int n, std::uint64_t seed)
{
  TetMesh mesh;
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < n; ++i)
    mesh.addVertex(unit(random), unit(random), unit(random));
  DelaunayResult r = buildDelaunay(mesh);
  EXPECT_TRUE(r.ok) << r.error;
  return mesh;
}

// Live tets whose interior the segment (a,b) meets.
std::vector<TetId> tetsCutBy(const TetMesh& mesh, VertexId a, VertexId b)
{
  std::vector<TetId> cut;
  const double* s[2] = { mesh.point(a), mesh.point(b) };
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    const double* p[4] = { mesh.point(mesh.vertex(t, 0)),
      mesh.point(mesh.vertex(t, 1)),
      mesh.point(mesh.vertex(t, 2)),
      mesh.point(mesh.vertex(t, 3)) };
    if (geometry::simplexMeetsTetInterior(s, 2, p))
      cut.push_back(t);
  }
  return cut;
}

long double totalVolume(const TetMesh& mesh)
{
  return volumeWithoutVertices(mesh, mesh.vertexCount());
}

} // namespace

TEST(CavityCone, RefillsCavitiesOfRandomSegmentsExactly)
{
  TetMesh mesh = randomDelaunay(400, 7);
  std::mt19937_64 random(11);
  std::uniform_int_distribution<VertexId> pick(0, 399);
  int refilled = 0, refused = 0;
  for (int attempt = 0; attempt < 200; ++attempt)
  {
    VertexTetIndex index;
    index.rebuild(mesh);
    const VertexId a = pick(random), b = pick(random);
    if (a == b || findEdge(mesh, index, a, b) >= 0)
      continue;
    std::vector<TetId> cavity = tetsCutBy(mesh, a, b);
    // Keep every edge that the Delaunay mesh has between two of the first 100 points.
    auto keep = [](VertexId u, VertexId v) { return u < 100 && v < 100; };
    std::vector<TetVertices> cone;
    const long double before = totalVolume(mesh);
    const TetId liveBefore = mesh.liveTetCount();
    if (!coneFromVertex(mesh, a, cavity, keep, {}, cone))
    {
      ++refused;
      EXPECT_EQ(mesh.liveTetCount(), liveBefore);
      continue;
    }
    std::vector<std::array<VertexId, 2>> kept;
    for (TetId t : cavity)
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          if (keep(mesh.vertex(t, i), mesh.vertex(t, j)))
            kept.push_back({ mesh.vertex(t, i), mesh.vertex(t, j) });
    replaceTets(mesh, index, cavity, cone);
    ++refilled;
    ASSERT_EQ(checkOrientation(mesh), "");
    ASSERT_EQ(checkAdjacency(mesh, true), "");
    ASSERT_EQ(checkVerticesPresent(mesh, mesh.vertexCount()), "");
    EXPECT_NEAR(static_cast<double>(totalVolume(mesh) / before), 1.0, 1e-12);
    EXPECT_GE(findEdge(mesh, index, a, b), 0) << "the cone from a has the edge (a,b)";
    for (const auto& e : kept)
      EXPECT_GE(findEdge(mesh, index, e[0], e[1]), 0) << e[0] << "-" << e[1];
  }
  std::printf("  %d cavities refilled, %d refused\n", refilled, refused);
  EXPECT_GE(refilled, 20);
}

TEST(CavityCone, NeverCrossesAConstrainedFace)
{
  TetMesh mesh = randomDelaunay(200, 3);
  VertexTetIndex index;
  index.rebuild(mesh);
  int tried = 0;
  for (VertexId a = 0; a < 50; ++a)
  {
    const VertexId b = 199 - a;
    if (findEdge(mesh, index, a, b) >= 0)
      continue;
    std::vector<TetId> cavity = tetsCutBy(mesh, a, b);
    if (cavity.size() < 2)
      continue;
    // Constrain the faces between the cavity's first tet and its neighbours in the cavity.
    const TetId first = cavity[0];
    bool constrained = false;
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = mesh.neighbor(first, f);
      if (n != kNoNeighbor && std::find(cavity.begin(), cavity.end(), faceTet(n)) != cavity.end())
      {
        mesh.setConstrained(first, f, true);
        mesh.setConstrained(faceTet(n), faceIndex(n), true);
        constrained = true;
      }
    }
    if (!constrained)
      continue;
    ++tried;
    std::vector<TetVertices> cone;
    EXPECT_FALSE(coneFromVertex(mesh, a, cavity, {}, {}, cone)) << a << "-" << b;
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = mesh.neighbor(first, f);
      mesh.setConstrained(first, f, false);
      if (n != kNoNeighbor)
        mesh.setConstrained(faceTet(n), faceIndex(n), false);
    }
  }
  EXPECT_GE(tried, 5);
}

// A box whose bottom face has cells of 30:1 or more, each bottom point at z = 0 or, at random,
// one rounding step below: the face is folded at the scale of rounding (like the bottom plate
// of netgen's hinge.stl, whose recovery failed for want of room for a Steiner point). The
// Delaunay mesh fills the folds with flat tets; refilling cavities recovers the edges they
// hide without the Steiner points (deterministic counts).
TEST(CavityCone, RecoversAFaceFoldedByRounding)
{
  int steinerWithout = 0, steinerWith = 0, cones = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed)
  {
    Surface s = box({ 0, 0, 0 },
      { 50, 25, 10 },
      { static_cast<int>(20 + 5 * seed),
        static_cast<int>(1 + seed % 3),
        static_cast<int>(1 + seed % 2) });
    std::mt19937_64 random(seed);
    for (std::size_t k = 2; k < s.points.size(); k += 3)
      if (s.points[k] == 0 && random() % 2)
        s.points[k] = -8.881784197001252e-16;
    SurfaceInput input;
    ASSERT_EQ(buildSurfaceInput(
                s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount(), input),
      "");
    for (bool refill : { false, true })
    {
      TetMesh mesh;
      mesh.coords = s.points;
      ASSERT_TRUE(buildDelaunay(mesh).ok);
      RecoveryOptions options;
      options.refillCavities = refill;
      RecoveryResult r = recoverBoundary(mesh, input, options);
      ASSERT_TRUE(r.ok) << "seed " << seed << ": " << r.error;
      EXPECT_EQ(checkOrientation(mesh), "");
      EXPECT_EQ(checkAdjacency(mesh, true), "");
      (refill ? steinerWith : steinerWithout) += static_cast<int>(r.steinerVertices.size());
      if (refill)
        cones += r.cavityCones;
      else
        EXPECT_EQ(r.cavityCones, 0);
    }
    MesherResult r =
      meshSurface(s.points.data(), s.pointCount(), s.triangles.data(), s.triangleCount());
    EXPECT_EQ(checkMesh(s, r, std::vector<int>(s.triangleCount(), 1), 1), "") << "seed " << seed;
  }
  std::printf("  Steiner points %d without refills, %d with %d refills\n",
    steinerWithout,
    steinerWith,
    cones);
  EXPECT_GE(cones, 5);
  EXPECT_LT(steinerWith, steinerWithout);
}
