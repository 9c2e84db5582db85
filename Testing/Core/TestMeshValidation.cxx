// The validation functions must accept valid meshes and name each kind of defect.
#include "Delaunay.h"
#include "MeshValidation.h"

#include <gtest/gtest.h>

#include <random>
#include <utility>

using namespace tetmesher;

namespace
{

TetMesh validMesh()
{
  TetMesh mesh;
  std::mt19937_64 gen(1);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 200; ++i)
    mesh.addVertex(u(gen), u(gen), u(gen));
  EXPECT_TRUE(buildDelaunay(mesh).ok);
  return mesh;
}

TetId firstInteriorTet(const TetMesh& mesh)
{
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (mesh.isDeleted(t))
      continue;
    bool interior = true;
    for (int f = 0; f < 4; ++f)
      interior = interior && mesh.neighbor(t, f) != kNoNeighbor;
    if (interior)
      return t;
  }
  return -1;
}

} // namespace

TEST(MeshValidation, AcceptsValidDelaunayMesh)
{
  TetMesh mesh = validMesh();
  EXPECT_EQ(checkOrientation(mesh), "");
  EXPECT_EQ(checkAdjacency(mesh, true), "");
  EXPECT_EQ(checkDelaunay(mesh), "");
  EXPECT_EQ(checkVerticesPresent(mesh, mesh.vertexCount()), "");
  EXPECT_EQ(validateDelaunayMesh(mesh, mesh.vertexCount()), "");
}

TEST(MeshValidation, DetectsInvertedTet)
{
  TetMesh mesh = validMesh();
  const TetId t = firstInteriorTet(mesh);
  std::swap(mesh.tets[4 * t], mesh.tets[4 * t + 1]);
  const std::string msg = checkOrientation(mesh);
  EXPECT_NE(msg.find("inverted"), std::string::npos) << msg;
}

TEST(MeshValidation, DetectsFlatAndRepeatedVertices)
{
  TetMesh mesh;
  for (int i = 0; i < 4; ++i)
    mesh.addVertex(i, 0, 0);
  mesh.addTet(0, 1, 2, 3);
  EXPECT_NE(checkOrientation(mesh).find("flat"), std::string::npos);
  mesh.tets[3] = 0;
  EXPECT_NE(checkOrientation(mesh).find("repeats"), std::string::npos);
}

TEST(MeshValidation, DetectsBrokenAdjacency)
{
  TetMesh mesh = validMesh();
  const TetId t = firstInteriorTet(mesh);
  const FaceRef n = mesh.neighbor(t, 0);
  // One-sided link.
  mesh.neighbors[4 * t] = mesh.neighbor(t, 1);
  EXPECT_NE(checkAdjacency(mesh).find("does not point back"), std::string::npos);
  mesh.neighbors[4 * t] = n;
  EXPECT_EQ(checkAdjacency(mesh), "");
  // Link to a deleted tet.
  TetMesh copy = mesh;
  copy.deleteTet(faceTet(n));
  EXPECT_NE(checkAdjacency(copy).find("not a live tet"), std::string::npos);
  // Constraint flag on one side only.
  mesh.setConstrained(t, 0, true);
  EXPECT_EQ(checkAdjacency(mesh, false), "");
  EXPECT_NE(checkAdjacency(mesh, true).find("one side"), std::string::npos);
}

TEST(MeshValidation, DetectsNonDelaunayFace)
{
  // Two tets glued on a face whose opposite vertex lies inside the other's circumsphere.
  TetMesh mesh;
  mesh.addVertex(0, 0, 0);
  mesh.addVertex(1, 0, 0);
  mesh.addVertex(0, 1, 0);
  mesh.addVertex(0.3, 0.3, 1);     // apex above
  mesh.addVertex(0.3, 0.3, -0.05); // apex just below: inside the upper tet's circumsphere
  // Positive tets: (0,2,1,3) has orient3d > 0 (3 above plane of ccw-from-above 0,1,2 ...).
  TetId up = mesh.addTet(0, 1, 2, 3);
  TetId down = mesh.addTet(0, 2, 1, 4);
  if (!checkOrientation(mesh).empty())
  {
    std::swap(mesh.tets[4 * up], mesh.tets[4 * up + 1]);
    std::swap(mesh.tets[4 * down], mesh.tets[4 * down + 1]);
  }
  ASSERT_EQ(checkOrientation(mesh), "");
  // Glue the shared face (the one opposite each apex, face 3).
  mesh.glue(up, 3, down, 3);
  ASSERT_EQ(checkAdjacency(mesh), "");
  const std::string msg = checkDelaunay(mesh);
  EXPECT_NE(msg.find("inside its circumsphere"), std::string::npos) << msg;
  // A constrained face is exempt.
  mesh.setConstrained(up, 3, true);
  mesh.setConstrained(down, 3, true);
  EXPECT_EQ(checkDelaunay(mesh, true), "");
  EXPECT_NE(checkDelaunay(mesh, false), "");
}

TEST(MeshValidation, DetectsMissingVertex)
{
  TetMesh mesh = validMesh();
  mesh.addVertex(0.5, 0.5, 0.5); // never inserted
  const std::string msg = checkVerticesPresent(mesh, mesh.vertexCount());
  EXPECT_NE(msg.find("is in no tet"), std::string::npos) << msg;
  EXPECT_EQ(checkVerticesPresent(mesh, mesh.vertexCount(), { mesh.vertexCount() - 1 }), "");
}
