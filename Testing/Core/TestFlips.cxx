// Local transformations (Flips.h), flip sequences (DeepEdgeRemoval.h), topology edits
// (MeshTopology.h), Steiner point removal
// (SteinerRemoval.h) and the exact intersection tests of recovery (RecoveryGeometry.h), on
// small hand-built meshes.
#include "DeepEdgeRemoval.h"
#include "Delaunay.h"
#include "Flips.h"
#include "MeshTopology.h"
#include "MeshValidation.h"
#include "Predicates.h"
#include "RecoveryGeometry.h"
#include "SteinerRemoval.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <random>

using namespace tetmesher;

namespace
{

// Builds a mesh from points and positively oriented tets, gluing shared faces.
TetMesh buildMesh(const std::vector<std::array<double, 3>>& points,
  const std::vector<TetVertices>& tets)
{
  TetMesh mesh;
  for (const auto& p : points)
    mesh.addVertex(p[0], p[1], p[2]);
  std::map<std::array<VertexId, 3>, FaceRef> open;
  for (const auto& v : tets)
  {
    TetId t = mesh.addTet(v[0], v[1], v[2], v[3]);
    for (int f = 0; f < 4; ++f)
    {
      std::array<VertexId, 3> key = {
        v[kFaceVertices[f][0]], v[kFaceVertices[f][1]], v[kFaceVertices[f][2]]
      };
      std::sort(key.begin(), key.end());
      auto it = open.find(key);
      if (it == open.end())
        open.emplace(key, makeFaceRef(t, f));
      else
      {
        mesh.glue(t, f, faceTet(it->second), faceIndex(it->second));
        open.erase(it);
      }
    }
  }
  return mesh;
}

TetVertices positive(const TetMesh& mesh, VertexId a, VertexId b, VertexId c, VertexId d)
{
  if (predicates::orient3d(mesh.point(a), mesh.point(b), mesh.point(c), mesh.point(d)) < 0)
    std::swap(a, b);
  return { a, b, c, d };
}

long double volume(const TetMesh& mesh)
{
  return volumeWithoutVertices(mesh, mesh.vertexCount());
}

// Two tets (x,y,z,a) and (x,y,z,w) on either side of the triangle xyz.
TetMesh twoTets(double wx)
{
  std::vector<std::array<double, 3>> p = {
    { 1, 0, 0 }, { -0.5, 1, 0 }, { -0.5, -1, 0 }, { 0, 0, 1 }, { wx, 0, -1 }
  };
  TetMesh probe = buildMesh(p, {});
  return buildMesh(p, { positive(probe, 0, 1, 2, 3), positive(probe, 0, 2, 1, 4) });
}

} // namespace

TEST(Flips, Flip23ThenEdgeRemovalRestores)
{
  TetMesh mesh = twoTets(0.0);
  VertexTetIndex index;
  index.rebuild(mesh);
  const long double before = volume(mesh);
  FlipCandidate c;
  // Face opposite the apex 3 of tet 0.
  int f = localIndex(mesh, 0, 3);
  ASSERT_TRUE(flip23Candidate(mesh, 0, f, {}, c));
  ASSERT_EQ(c.newTets.size(), 3u);
  replaceTets(mesh, index, c.oldTets, c.newTets);
  EXPECT_EQ(mesh.liveTetCount(), 3);
  EXPECT_EQ(checkOrientation(mesh), "");
  EXPECT_EQ(checkAdjacency(mesh, true), "");
  EXPECT_NEAR(static_cast<double>(volume(mesh)), static_cast<double>(before), 1e-15);
  // The new edge (3,4) has a shell of three tets: removing it is the 3-2 flip.
  TetId t = findEdge(mesh, index, 3, 4);
  ASSERT_GE(t, 0);
  ASSERT_TRUE(edgeRemovalCandidate(mesh, t, 3, 4, {}, c));
  EXPECT_EQ(c.newTets.size(), 2u);
  replaceTets(mesh, index, c.oldTets, c.newTets);
  EXPECT_EQ(mesh.liveTetCount(), 2);
  EXPECT_EQ(findEdge(mesh, index, 3, 4), -1);
  EXPECT_GE(findFace(mesh, index, 0, 1, 2), 0);
  EXPECT_EQ(checkOrientation(mesh), "");
  EXPECT_EQ(checkAdjacency(mesh, true), "");
}

TEST(Flips, Flip23RefusedWhenApexSegmentMissesFace)
{
  // w far to the side: segment (a,w) passes outside the triangle, one new tet would be
  // inverted.
  TetMesh mesh = twoTets(3.0);
  FlipCandidate c;
  EXPECT_FALSE(flip23Candidate(mesh, 0, localIndex(mesh, 0, 3), {}, c));
}

TEST(Flips, ConstrainedFaceIsNeverFlipped)
{
  TetMesh mesh = twoTets(0.0);
  int f = localIndex(mesh, 0, 3);
  mesh.setConstrained(0, f, true);
  FaceRef n = mesh.neighbor(0, f);
  mesh.setConstrained(faceTet(n), faceIndex(n), true);
  FlipCandidate c;
  EXPECT_FALSE(flip23Candidate(mesh, 0, f, {}, c));
}

TEST(Flips, EdgeRemovalOfAnOctahedronDiagonalAndFlagsKept)
{
  // Octahedron split into 4 tets around its vertical axis (4,5): removal gives 4 tets (4-4).
  std::vector<std::array<double, 3>> p = {
    { 1, 0, 0 }, { 0, 1, 0 }, { -1, 0, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 }
  };
  TetMesh probe = buildMesh(p, {});
  std::vector<TetVertices> tets;
  for (int k = 0; k < 4; ++k)
    tets.push_back(positive(probe, 4, 5, k, (k + 1) % 4));
  TetMesh mesh = buildMesh(p, tets);
  // Flag one outer face; it must survive the flip.
  FaceRef outer = -1;
  for (int f = 0; f < 4 && outer < 0; ++f)
  {
    if (mesh.vertex(0, f) == 5)
      outer = makeFaceRef(0, f);
  }
  ASSERT_GE(outer, 0);
  mesh.setConstrained(faceTet(outer), faceIndex(outer), true);
  VertexTetIndex index;
  index.rebuild(mesh);
  FlipCandidate c;
  // Prefer any triangulation; the cost counts nothing.
  ASSERT_TRUE(edgeRemovalCandidate(mesh, 0, 4, 5, {}, c));
  EXPECT_EQ(c.newTets.size(), 4u);
  replaceTets(mesh, index, c.oldTets, c.newTets);
  EXPECT_EQ(findEdge(mesh, index, 4, 5), -1);
  EXPECT_EQ(checkOrientation(mesh), "");
  EXPECT_EQ(checkAdjacency(mesh, false), "");
  int flagged = 0;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    for (int f = 0; f < 4 && !mesh.isDeleted(t); ++f)
      flagged += mesh.isConstrained(t, f);
  }
  EXPECT_EQ(flagged, 1);
}

TEST(Flips, ConstrainedFaceAroundEdgeBlocksRemoval)
{
  std::vector<std::array<double, 3>> p = {
    { 1, 0, 0 }, { 0, 1, 0 }, { -1, 0, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 }
  };
  TetMesh probe = buildMesh(p, {});
  std::vector<TetVertices> tets;
  for (int k = 0; k < 4; ++k)
    tets.push_back(positive(probe, 4, 5, k, (k + 1) % 4));
  TetMesh mesh = buildMesh(p, tets);
  // Face (4,5,ring vertex) of tet 0, i.e. the face opposite one of its ring vertices.
  int f = mesh.vertex(0, 0) != 4 && mesh.vertex(0, 0) != 5
    ? 0
    : (mesh.vertex(0, 1) != 4 && mesh.vertex(0, 1) != 5 ? 1 : 2);
  mesh.setConstrained(0, f, true);
  FaceRef n = mesh.neighbor(0, f);
  mesh.setConstrained(faceTet(n), faceIndex(n), true);
  FlipCandidate c;
  EXPECT_FALSE(edgeRemovalCandidate(mesh, 0, 4, 5, {}, c));
}

TEST(Flips, CostSteersEdgeRemoval)
{
  // Same octahedron: the ring (0,1,2,3) has two triangulations; a cost on edge (1,3) makes the
  // removal choose the diagonal (0,2).
  std::vector<std::array<double, 3>> p = {
    { 1, 0, 0 }, { 0, 1, 0 }, { -1, 0, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 }
  };
  TetMesh probe = buildMesh(p, {});
  std::vector<TetVertices> tets;
  for (int k = 0; k < 4; ++k)
    tets.push_back(positive(probe, 4, 5, k, (k + 1) % 4));
  TetMesh mesh = buildMesh(p, tets);
  FlipCost cost;
  cost.edge = [](VertexId a, VertexId b) { return std::minmax(a, b) == std::minmax(1, 3) ? 5 : 0; };
  FlipCandidate c;
  ASSERT_TRUE(edgeRemovalCandidate(mesh, 0, 4, 5, cost, c));
  EXPECT_EQ(c.newCost, 0);
  VertexTetIndex index;
  index.rebuild(mesh);
  replaceTets(mesh, index, c.oldTets, c.newTets);
  EXPECT_GE(findEdge(mesh, index, 0, 2), 0);
  EXPECT_EQ(findEdge(mesh, index, 1, 3), -1);
}

TEST(Flips, SteinerPointRemovedByFourToOne)
{
  std::vector<std::array<double, 3>> p = {
    { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0.2, 0.2, 0.2 }
  };
  TetMesh probe = buildMesh(p, {});
  std::vector<TetVertices> tets;
  const int faces[4][3] = { { 0, 1, 2 }, { 0, 1, 3 }, { 0, 2, 3 }, { 1, 2, 3 } };
  for (auto& f : faces)
    tets.push_back(positive(probe, f[0], f[1], f[2], 4));
  TetMesh mesh = buildMesh(p, tets);
  std::vector<VertexId> steiner = { 4 };
  EXPECT_EQ(removeSteinerPoints(mesh, steiner), 1);
  EXPECT_TRUE(steiner.empty());
  EXPECT_EQ(mesh.liveTetCount(), 1);
  EXPECT_EQ(checkOrientation(mesh), "");
}

namespace
{
// The first four points of p as a positively oriented tet in t; false when they are coplanar.
bool positiveTetOf(const double (*p)[3], const double* t[4])
{
  for (int k = 0; k < 4; ++k)
    t[k] = p[k];
  const int orientation = predicates::orient3d(t[0], t[1], t[2], t[3]);
  if (orientation < 0)
    std::swap(t[0], t[1]);
  return orientation != 0;
}
} // namespace

// DeepEdgeRemoval::onCreated names every tet that a kept sequence or an undo puts in a slot
// (a caller's per-tet data, such as FlatTetRemoval's regions, depends on it): after each
// attempt on the edges of a Delaunay mesh, every live slot whose tet changed was named.
TEST(DeepEdgeRemoval, OnCreatedNamesEveryNewTet)
{
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(0, 1);
  TetMesh mesh;
  for (int i = 0; i < 300; ++i)
    mesh.addVertex(u(rng), u(rng), u(rng));
  ASSERT_TRUE(buildDelaunay(mesh).ok);
  VertexTetIndex index;
  index.rebuild(mesh);
  DeepEdgeRemoval deep(mesh, index);
  std::vector<char> named;
  deep.onCreated = [&](TetId t)
  {
    if (named.size() <= static_cast<std::size_t>(t))
      named.resize(static_cast<std::size_t>(t) + 1, 0);
    named[static_cast<std::size_t>(t)] = 1;
  };
  auto snapshot = [&]
  {
    std::vector<TetVertices> tets(static_cast<std::size_t>(mesh.tetCapacity()), { -1, -1, -1, -1 });
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
      if (!mesh.isDeleted(t))
        tets[static_cast<std::size_t>(t)] = {
          mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3)
        };
    return tets;
  };
  // Every live slot that holds another tet than in `before` was named since.
  auto unnamedChanges = [&](const std::vector<TetVertices>& before)
  {
    int unnamed = 0;
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    {
      const std::size_t s = static_cast<std::size_t>(t);
      const bool changed = !mesh.isDeleted(t) &&
        (s >= before.size() ||
          before[s] !=
            TetVertices{
              mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2), mesh.vertex(t, 3) });
      if (changed && (s >= named.size() || !named[s]))
        ++unnamed;
    }
    return unnamed;
  };
  const FlipCost validity;
  int removed = 0, undone = 0, tried = 0;
  for (TetId t = 0; t < mesh.tetCapacity() && tried < 400; t += 7)
  {
    if (mesh.isDeleted(t))
      continue;
    const VertexId p = mesh.vertex(t, 0), q = mesh.vertex(t, 1);
    ++tried;
    named.assign(named.size(), 0);
    const std::vector<TetVertices> before = snapshot();
    deep.resetJournal();
    int budget = 8;
    const bool ok = deep.remove(p, q, 1, validity, budget);
    ASSERT_EQ(unnamedChanges(before), 0) << "after removing (" << p << "," << q << ")";
    // Undo every other success, and every failure, as the callers do.
    if (ok && removed <= undone)
    {
      ++removed;
      deep.resetJournal();
      continue;
    }
    const std::vector<TetVertices> beforeUndo = snapshot();
    named.assign(named.size(), 0);
    deep.undoTo(0, 0);
    ASSERT_EQ(unnamedChanges(beforeUndo), 0) << "after undoing (" << p << "," << q << ")";
    undone += ok ? 1 : 0;
  }
  EXPECT_EQ(checkOrientation(mesh), "");
  EXPECT_EQ(checkAdjacency(mesh), "");
  // Both paths ran often enough to mean something.
  EXPECT_GT(removed, 20);
  EXPECT_GT(undone, 20);
  std::printf("%d edges tried: %d removals kept, %d undone\n", tried, removed, undone);
}

TEST(RecoveryGeometry, SegmentAndTriangle)
{
  const double p[3] = { 0, 0, 0 }, q[3] = { 1, 0, 0 }, r[3] = { 0, 1, 0 };
  const double above[3] = { 0.2, 0.2, 1 }, below[3] = { 0.2, 0.2, -1 }, far[3] = { 2, 2, -1 };
  EXPECT_TRUE(geometry::segmentMeetsTriangle(above, below, p, q, r));
  EXPECT_FALSE(geometry::segmentMeetsTriangle(above, far, p, q, r));
  // Ends on the plane: the open segment does not meet the triangle.
  const double onPlane[3] = { 0.2, 0.2, 0 };
  EXPECT_FALSE(geometry::segmentMeetsTriangle(above, onPlane, p, q, r));
  // Coplanar, crossing the triangle.
  const double a[3] = { -1, 0.25, 0 }, b[3] = { 2, 0.25, 0 };
  EXPECT_TRUE(geometry::segmentMeetsTriangle(a, b, p, q, r));
  // Coplanar along an edge line only: no interior point.
  const double c[3] = { -1, 0, 0 }, d[3] = { 2, 0, 0 };
  EXPECT_FALSE(geometry::segmentMeetsTriangle(c, d, p, q, r));
  // Through a triangle edge exactly: not the relative interior.
  const double e[3] = { 0.5, 0, 1 }, g[3] = { 0.5, 0, -1 };
  EXPECT_FALSE(geometry::segmentMeetsTriangle(e, g, p, q, r));
}

TEST(RecoveryGeometry, SimplexInTetAgreesWithSeparation)
{
  // Segments and triangles with a vertex of the tet are decided by orientations at that
  // vertex, other segments by their crossings with the face planes: the same answers as the
  // separating-plane search, on small integer coordinates (many coplanar and collinear
  // configurations) and on random ones.
  std::mt19937 rng(12345);
  int meets[2] = { 0, 0 }; // per simplex kind: both answers must occur often
  int missed[2] = { 0, 0 };
  for (int trial = 0; trial < 400000; ++trial)
  {
    const bool lattice = (trial / 2) % 2 == 0;
    std::uniform_int_distribution<int> cell(-2, 2);
    std::uniform_real_distribution<double> any(-1.0, 1.0);
    double p[7][3];
    for (auto& x : p)
      for (double& c : x)
        c = lattice ? cell(rng) : any(rng);
    const double* t[4];
    if (!positiveTetOf(p, t))
      continue;
    // A simplex from a tet vertex (every other segment: from anywhere); its other vertices
    // are new points or other tet vertices.
    const int count = 2 + trial % 2;
    const double* simplex[3] = { t[rng() % 4], p[4], p[5] };
    if (count == 2 && (trial / 4) % 2 == 0)
      simplex[0] = p[6];
    if (rng() % 4 == 0)
      simplex[1] = t[rng() % 4];
    if (count == 3 && rng() % 4 == 0)
      simplex[2] = t[rng() % 4];
    std::shuffle(simplex, simplex + count, rng);
    const bool distinct = simplex[0] != simplex[1] &&
      (count == 2 || (simplex[0] != simplex[2] && simplex[1] != simplex[2]));
    const bool flat = count == 2
      ? (simplex[0][0] == simplex[1][0] && simplex[0][1] == simplex[1][1] &&
          simplex[0][2] == simplex[1][2])
      : (predicates::orient2d(simplex[0], simplex[1], simplex[2], 0) == 0 &&
          predicates::orient2d(simplex[0], simplex[1], simplex[2], 1) == 0 &&
          predicates::orient2d(simplex[0], simplex[1], simplex[2], 2) == 0);
    if (!distinct || flat)
      continue;
    // A point in the relative interior of a tet edge or face is not a valid mesh input.
    const bool answer = geometry::simplexMeetsTetInterior(simplex, count, t);
    ASSERT_EQ(answer, geometry::simplexMeetsTetInteriorBySeparation(simplex, count, t))
      << "trial " << trial;
    ++(answer ? meets : missed)[count - 2];
  }
  for (int kind = 0; kind < 2; ++kind)
  {
    EXPECT_GT(meets[kind], 5000) << kind;
    EXPECT_GT(missed[kind], 5000) << kind;
  }
  std::printf("segments %d meet, %d miss; triangles %d meet, %d miss\n",
    meets[0],
    missed[0],
    meets[1],
    missed[1]);
}

TEST(RecoveryGeometry, SegmentFromVertexMissesTetOnlyWhenNothingMeets)
{
  // The cone test at a tet vertex a rules a tet out for the open segment (a, b): then neither
  // its interior nor any of its faces or edges may meet the segment. When it does not rule the
  // tet out, b lies in the closed cone, so something of the tet near a does. Small integer
  // coordinates give many coplanar configurations (b on a face plane through a).
  std::mt19937 rng(2026);
  int ruledOut = 0, kept = 0;
  for (int trial = 0; trial < 200000; ++trial)
  {
    std::uniform_int_distribution<int> cell(-2, 2);
    double p[5][3];
    for (auto& x : p)
      for (double& c : x)
        c = cell(rng);
    const double* t[4];
    if (!positiveTetOf(p, t))
      continue;
    const int i = static_cast<int>(rng() % 4);
    const double* a = t[i];
    const double* b = p[4];
    bool onTetVertex = false;
    for (const double* v : t)
      onTetVertex = onTetVertex || (v[0] == b[0] && v[1] == b[1] && v[2] == b[2]);
    if (onTetVertex)
      continue;
    const double* segment[2] = { a, b };
    bool meets = geometry::simplexMeetsTetInterior(segment, 2, t);
    for (int f = 0; f < 4 && !meets; ++f)
    {
      const double* face[3];
      for (int k = 0, n = 0; k < 4; ++k)
        if (k != f)
          face[n++] = t[k];
      meets = geometry::segmentMeetsTriangle(a, b, face[0], face[1], face[2]);
    }
    for (int u = 0; u < 4 && !meets; ++u)
      for (int v = u + 1; v < 4 && !meets; ++v)
        meets = u != i && v != i && geometry::segmentsCross(a, b, t[u], t[v]);
    if (geometry::segmentFromVertexMissesTet(t, i, b))
    {
      ASSERT_FALSE(meets) << "trial " << trial;
      ++ruledOut;
    }
    else
      ++kept;
  }
  EXPECT_GT(ruledOut, 20000);
  EXPECT_GT(kept, 20000);
}

TEST(RecoveryGeometry, SegmentsCrossAndSimplexInTet)
{
  const double a[3] = { 0, 0, 0 }, b[3] = { 1, 1, 0 }, c[3] = { 1, 0, 0 }, d[3] = { 0, 1, 0 };
  EXPECT_TRUE(geometry::segmentsCross(a, b, c, d));
  const double e[3] = { 0, 1, 1 };
  EXPECT_FALSE(geometry::segmentsCross(a, b, c, e));
  EXPECT_FALSE(geometry::segmentsCross(a, c, a, d)); // shared end point only
  const double t0[3] = { 0, 0, 0 }, t1[3] = { 1, 0, 0 }, t2[3] = { 0, 1, 0 }, t3[3] = { 0, 0, 1 };
  const double* tet[4] = { t0, t2, t1, t3 }; // positively oriented
  const double in1[3] = { 0.1, 0.1, 0.1 }, out1[3] = { 2, 2, 2 };
  const double* seg[2] = { in1, out1 };
  EXPECT_TRUE(geometry::simplexMeetsTetInterior(seg, 2, tet));
  const double o1[3] = { -1, -1, -1 }, o2[3] = { -1, 2, -1 };
  const double* away[2] = { o1, o2 };
  EXPECT_FALSE(geometry::simplexMeetsTetInterior(away, 2, tet));
  // An edge of the tet does not meet its interior; a face diagonal-like segment on a face
  // does not either.
  const double* edge[2] = { t0, t1 };
  EXPECT_FALSE(geometry::simplexMeetsTetInterior(edge, 2, tet));
  const double* face[3] = { t0, t1, t2 };
  EXPECT_FALSE(geometry::simplexMeetsTetInterior(face, 3, tet));
  // A triangle slicing the tet.
  const double s0[3] = { -1, -1, 0.2 }, s1[3] = { 3, -1, 0.2 }, s2[3] = { -1, 3, 0.2 };
  const double* slice[3] = { s0, s1, s2 };
  EXPECT_TRUE(geometry::simplexMeetsTetInterior(slice, 3, tet));
  EXPECT_TRUE(geometry::pointInsideTet(in1, tet));
  EXPECT_FALSE(geometry::pointInsideTet(t0, tet));
  const double onFace[3] = { 0.25, 0.25, 0 };
  EXPECT_TRUE(geometry::pointOnTriangle(onFace, t0, t1, t2));
  EXPECT_TRUE(geometry::pointOnTriangle(t1, t0, t1, t2));
  EXPECT_FALSE(geometry::pointOnTriangle(in1, t0, t1, t2));
}
