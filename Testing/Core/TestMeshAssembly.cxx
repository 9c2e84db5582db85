// assembleRegionMesh / extractRegionMesh: adjacency, constrained boundary and interface faces,
// round trip.
#include "MeshAssembly.h"
#include "Mesher.h"

#include <gtest/gtest.h>

namespace
{
// Two unit cubes side by side (x in [0,1] and [1,2]), 12 triangles each, sharing the face
// x = 1: a multi-material surface (the shared face's 2 triangles listed once).
void TwoCubes(std::vector<double>& points, std::vector<std::int32_t>& triangles)
{
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        points.insert(points.end(), { double(i), double(j), double(k) });
  auto id = [](int i, int j, int k) { return 4 * i + 2 * j + k; };
  auto quad = [&](int a, int b, int c, int d) {
    triangles.insert(triangles.end(), { a, b, c, a, c, d });
  };
  for (int c = 0; c < 2; ++c)
  {
    int x0 = c, x1 = c + 1;
    if (c == 0)
      quad(id(x0, 0, 0), id(x0, 0, 1), id(x0, 1, 1), id(x0, 1, 0)); // x = 0, outward -x
    quad(id(x1, 0, 0), id(x1, 1, 0), id(x1, 1, 1), id(x1, 0, 1));   // x = 1 (shared) / x = 2
    quad(id(x0, 0, 0), id(x1, 0, 0), id(x1, 0, 1), id(x0, 0, 1));   // y = 0
    quad(id(x0, 1, 0), id(x0, 1, 1), id(x1, 1, 1), id(x1, 1, 0));   // y = 1
    quad(id(x0, 0, 0), id(x0, 1, 0), id(x1, 1, 0), id(x1, 0, 0));   // z = 0
    quad(id(x0, 0, 1), id(x1, 0, 1), id(x1, 1, 1), id(x0, 1, 1));   // z = 1
  }
}
} // namespace

TEST(MeshAssembly, RoundTripWithBoundaryAndInterfaceLocked)
{
  std::vector<double> points;
  std::vector<std::int32_t> triangles;
  TwoCubes(points, triangles);
  tetmesher::MesherResult result = tetmesher::meshSurface(points.data(),
    static_cast<std::int32_t>(points.size() / 3),
    triangles.data(),
    static_cast<std::int32_t>(triangles.size() / 3));
  ASSERT_TRUE(result.ok) << result.error;
  ASSERT_EQ(result.regionCount, 2);

  tetmesher::RegionMesh assembled;
  ASSERT_TRUE(
    tetmesher::assembleRegionMesh(result.points, result.tets, result.regionIds, assembled));
  const tetmesher::TetMesh& mesh = assembled.mesh;
  int constrainedSides = 0, hullSides = 0;
  for (tetmesher::TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    for (int f = 0; f < 4; ++f)
    {
      tetmesher::FaceRef n = mesh.neighbor(t, f);
      if (n == tetmesher::kNoNeighbor)
      {
        ++hullSides;
        EXPECT_TRUE(mesh.isConstrained(t, f));
        continue;
      }
      // Symmetric adjacency.
      EXPECT_EQ(mesh.neighbor(tetmesher::faceTet(n), tetmesher::faceIndex(n)),
        tetmesher::makeFaceRef(t, f));
      bool interface = assembled.region[static_cast<std::size_t>(t)] !=
        assembled.region[static_cast<std::size_t>(tetmesher::faceTet(n))];
      EXPECT_EQ(mesh.isConstrained(t, f), interface);
      constrainedSides += interface;
    }
  }
  // 20 outer boundary triangles, and the 2 interface triangles seen from both sides.
  EXPECT_EQ(hullSides, 20);
  EXPECT_EQ(constrainedSides, 4);

  std::vector<double> points2;
  std::vector<std::int32_t> tets2, regions2;
  tetmesher::extractRegionMesh(assembled, points2, tets2, regions2);
  EXPECT_EQ(points2, result.points);
  EXPECT_EQ(tets2, result.tets);
  EXPECT_EQ(regions2, result.regionIds);
}

TEST(MeshAssembly, RefusesAFaceOfThreeTets)
{
  std::vector<double> points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 1, 1, 1 };
  // Three tets on face (0,1,2).
  std::vector<std::int32_t> tets = { 0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 2, 5 };
  tetmesher::RegionMesh out;
  EXPECT_FALSE(tetmesher::assembleRegionMesh(points, tets, {}, out));
}

TEST(MeshAssembly, RefusesAVertexIdWithoutAPoint)
{
  std::vector<double> points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  tetmesher::RegionMesh out;
  EXPECT_TRUE(tetmesher::assembleRegionMesh(points, { 0, 1, 2, 3 }, {}, out));
  EXPECT_FALSE(tetmesher::assembleRegionMesh(points, { 0, 1, 2, 4 }, {}, out));
  EXPECT_FALSE(tetmesher::assembleRegionMesh(points, { 0, 1, -1, 3 }, {}, out));
}

TEST(MeshAssembly, InputFacesAreConstrainedInsideARegion)
{
  // Two tets of one region sharing face (0,1,2), opposite vertex 3 in the first (face 3) and
  // vertex 4 in the second (face 3): an inner facet only when named as an input face.
  std::vector<double> points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1 };
  const std::vector<std::int32_t> tets = { 0, 1, 2, 3, 0, 2, 1, 4 };
  tetmesher::RegionMesh plain, inner;
  ASSERT_TRUE(tetmesher::assembleRegionMesh(points, tets, { 0, 0 }, plain));
  EXPECT_FALSE(plain.mesh.isConstrained(0, 3));
  EXPECT_FALSE(plain.mesh.isConstrained(1, 3));
  ASSERT_TRUE(tetmesher::assembleRegionMesh(points, tets, { 0, 0 }, inner, { -1, 3 }));
  EXPECT_TRUE(inner.mesh.isConstrained(0, 3));
  EXPECT_TRUE(inner.mesh.isConstrained(1, 3));
  EXPECT_FALSE(tetmesher::assembleRegionMesh(points, tets, { 0, 0 }, inner, { 8 }));
}
