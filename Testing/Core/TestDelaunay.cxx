// Delaunay kernel: exact validity on random, degenerate (grid, sphere), clustered and
// duplicate-laden input; determinism; hull volume; constrained insertion.
#include "Delaunay.h"
#include "HilbertSort.h"
#include "MeshValidation.h"
#include "PointSets.h"
#include "Predicates.h"
#include "SmallLattice.h"

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

// farBox: the box tets only leave the convex hull of the input when the box is far enough
// that no Delaunay ball of a hull face reaches a box corner; hull tests ask for a far box.
void buildAndValidate(TetMesh& mesh, DelaunayResult* out = nullptr, bool farBox = false)
{
  const VertexId n = mesh.vertexCount();
  DelaunayOptions options;
  options.validate = true;
  if (farBox)
    options.boxEnlargement = 1e4;
  DelaunayResult r = buildDelaunay(mesh, options);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.firstBoxVertex, n);
  EXPECT_EQ(mesh.vertexCount(), n + 8);
  if (out)
    *out = r;
}

// Number of live tets; hull faces are exactly the 12 triangles of the box.
void expectBoxHull(const TetMesh& mesh)
{
  int hullFaces = 0;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (!mesh.isDeleted(t))
      for (int f = 0; f < 4; ++f)
        hullFaces += mesh.neighbor(t, f) == kNoNeighbor;
  EXPECT_EQ(hullFaces, 12);
}

} // namespace

TEST(Delaunay, EmptyAndTinyInputs)
{
  for (int n : { 0, 1, 2, 3, 4, 5 })
  {
    TetMesh mesh = randomPoints(n, 7);
    buildAndValidate(mesh);
    expectBoxHull(mesh);
  }
}

TEST(Delaunay, RandomPointsAreExactlyValid)
{
  for (int n : { 10000, 100000 })
  {
    TetMesh mesh = randomPoints(n, 42 + n);
    buildAndValidate(mesh);
    expectBoxHull(mesh);
  }
}

// Points on the skip list stay vertices of no tet; the rest is the Delaunay of the others,
// exactly valid, with large rounds in halves (40k points) or not, and the same as a build
// without the skipped points (the same tets, by coordinates).
TEST(Delaunay, SkippedPointsAreNotInserted)
{
  for (int n : { 2000, 40000 })
  {
    TetMesh mesh = randomPoints(n, 11 + n);
    std::vector<std::uint8_t> skip(static_cast<std::size_t>(n), 0);
    TetMesh kept;
    for (VertexId v = 0; v < n; ++v)
    {
      skip[static_cast<std::size_t>(v)] = v % 7 == 3;
      if (v % 7 != 3)
        kept.addVertex(mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2]);
    }
    DelaunayOptions options;
    options.validate = true; // every vertex present but the skipped ones
    options.boxEnlargement = 1e4;
    options.skip = skip.data();
    const DelaunayResult r = buildDelaunay(mesh, options);
    ASSERT_TRUE(r.ok) << r.error;
    std::vector<char> used(static_cast<std::size_t>(mesh.vertexCount()), 0);
    for (TetId t = 0; t < mesh.tetCapacity(); ++t)
      if (!mesh.isDeleted(t))
        for (int i = 0; i < 4; ++i)
          used[static_cast<std::size_t>(mesh.vertex(t, i))] = 1;
    for (VertexId v = 0; v < n; ++v)
      EXPECT_EQ(used[static_cast<std::size_t>(v)] != 0, v % 7 != 3) << v;
    // The same triangulation as the kept points alone: their tets (those without a box
    // corner; the box far away, so that they are the Delaunay of the points, whatever the
    // skipped points do to the bounding box), compared by coordinates.
    DelaunayOptions plain;
    plain.boxEnlargement = 1e4;
    const VertexId keptCount = kept.vertexCount();
    ASSERT_TRUE(buildDelaunay(kept, plain).ok);
    auto tetsByCoordinates = [](const TetMesh& m, VertexId points)
    {
      std::set<std::array<std::array<double, 3>, 4>> out;
      for (TetId t = 0; t < m.tetCapacity(); ++t)
      {
        if (m.isDeleted(t))
          continue;
        std::array<std::array<double, 3>, 4> tet;
        bool boxCorner = false;
        for (int i = 0; i < 4; ++i)
        {
          const VertexId v = m.vertex(t, i);
          boxCorner = boxCorner || v >= points;
          tet[static_cast<std::size_t>(i)] = { m.point(v)[0], m.point(v)[1], m.point(v)[2] };
        }
        std::sort(tet.begin(), tet.end());
        if (!boxCorner)
          out.insert(tet);
      }
      return out;
    };
    if (tetsByCoordinates(mesh, n) != tetsByCoordinates(kept, keptCount))
      ADD_FAILURE() << n << " points: the mesh differs from the kept points' own";
  }
}

TEST(Delaunay, GridIsValidAndFillsTheCube)
{
  // A 20^3 grid: every cell is cospherical, every grid plane coplanar.
  TetMesh mesh = gridPoints(20);
  DelaunayResult r;
  buildAndValidate(mesh, &r, true);
  // Removing the tets that touch the box leaves the convex hull: the cube [0,19]^3.
  EXPECT_NEAR(
    static_cast<double>(volumeWithoutVertices(mesh, r.firstBoxVertex)), 19.0 * 19 * 19, 1e-9);
}

TEST(Delaunay, PointsOnASphere)
{
  TetMesh mesh = pointsOnUnitSphere(20000, 3);
  // Exactly cospherical too: integer points on x^2+y^2+z^2 = 25*16.
  for (int x = -20; x <= 20; ++x)
    for (int y = -20; y <= 20; ++y)
      for (int z = -20; z <= 20; ++z)
        if (x * x + y * y + z * z == 400)
          mesh.addVertex(x + 100, y, z);
  buildAndValidate(mesh);
}

// The centre of many points on a sphere is in the circumsphere of every tet inside it: its
// cavity has hundreds of boundary vertices, more than the local numbering of the cone's
// gluing takes, so the edge hash table glues it.
TEST(Delaunay, HugeCavityAtTheCentreOfASphere)
{
  TetMesh mesh = pointsOnUnitSphere(400, 5);
  mesh.addVertex(0, 0, 0);
  buildAndValidate(mesh);
}

TEST(Delaunay, ClusteredPoints)
{
  TetMesh mesh;
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g;
  for (int c = 0; c < 20; ++c)
  {
    const double cx = u(gen) * 1000, cy = u(gen) * 1000, cz = u(gen) * 1000;
    const double spread = std::pow(10.0, -6 + 6 * u(gen));
    for (int i = 0; i < 2000; ++i)
      mesh.addVertex(cx + spread * g(gen), cy + spread * g(gen), cz + spread * g(gen));
  }
  buildAndValidate(mesh);
}

TEST(Delaunay, DuplicatesAreReportedNotInserted)
{
  TetMesh mesh = randomPoints(3000, 5);
  std::mt19937_64 gen(9);
  const VertexId original = mesh.vertexCount();
  for (int i = 0; i < 3000; ++i)
  {
    const VertexId src = static_cast<VertexId>(gen() % original);
    const double* p = mesh.point(src);
    mesh.addVertex(p[0], p[1], p[2]);
  }
  // And a small grid repeated three times.
  for (int rep = 0; rep < 3; ++rep)
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j)
        for (int k = 0; k < 5; ++k)
          mesh.addVertex(2 + i, j, k);
  DelaunayResult r;
  buildAndValidate(mesh, &r);
  ASSERT_EQ(r.duplicates.size(), r.duplicateOf.size());
  EXPECT_EQ(r.duplicates.size(), 3000u + 250u);
  for (std::size_t i = 0; i < r.duplicates.size(); ++i)
  {
    const double* a = mesh.point(r.duplicates[i]);
    const double* b = mesh.point(r.duplicateOf[i]);
    EXPECT_TRUE(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
    EXPECT_NE(r.duplicates[i], r.duplicateOf[i]);
  }
}

TEST(Delaunay, SameInputGivesIdenticalMesh)
{
  TetMesh a = randomPoints(20000, 77);
  TetMesh b = a;
  ASSERT_TRUE(buildDelaunay(a).ok);
  ASSERT_TRUE(buildDelaunay(b).ok);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.neighbors, b.neighbors);
  TetMesh g1 = gridPoints(12), g2 = gridPoints(12);
  ASSERT_TRUE(buildDelaunay(g1).ok);
  ASSERT_TRUE(buildDelaunay(g2).ok);
  EXPECT_EQ(g1.tets, g2.tets);
}

TEST(Delaunay, SmallLatticeBitsOfPointSets)
{
  auto bits = [](const TetMesh& mesh)
  {
    double lo[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
      for (VertexId v = 0; v < mesh.vertexCount(); ++v)
        lo[k] = v == 0 ? mesh.point(v)[k] : std::min(lo[k], mesh.point(v)[k]);
    return smallLatticeBits(mesh.coords.data(), mesh.vertexCount(), lo);
  };
  EXPECT_EQ(bits(gridPoints(100)), 7); // 0..99
  TetMesh shifted = gridPoints(9);     // 0..8 in steps of 2^-3, at 1000.5
  for (double& c : shifted.coords)
    c = 1000.5 + c / 8;
  EXPECT_EQ(bits(shifted), 4);
  TetMesh decimal = gridPoints(5); // steps of 0.1 are not a power of two
  for (double& c : decimal.coords)
    c *= 0.1;
  EXPECT_EQ(bits(decimal), 0);
  TetMesh wide;
  wide.addVertex(0, 0, 0);
  wide.addVertex(511, 3, 1);
  EXPECT_EQ(bits(wide), 9);
  wide.addVertex(512, 0, 0); // 10 bits: products could round
  EXPECT_EQ(bits(wide), 0);
  TetMesh one = gridPoints(4);
  one.addVertex(1.5, 2, std::nextafter(2.0, 3.0));
  EXPECT_EQ(bits(one), 0);
  TetMesh tiny = gridPoints(3); // exact, but products of differences would leave the normals
  for (double& c : tiny.coords)
    c = std::ldexp(c, -300);
  EXPECT_EQ(bits(tiny), 0);
  EXPECT_EQ(bits(randomPoints(100, 3)), 0);
  EXPECT_EQ(bits(TetMesh()), 0);
}

// The small-lattice evaluation (exact in doubles) must answer every test as the filtered
// predicates with their exact fallback do: the same tets, in the same slots, on lattices
// that take the serial insertion and the two halves, with duplicates among the points.
TEST(Delaunay, SmallLatticeGivesTheSameMesh)
{
  std::vector<TetMesh> inputs;
  inputs.push_back(gridPoints(12));
  TetMesh shifted = gridPoints(10);
  for (double& c : shifted.coords)
    c = -3.25 + c / 4;
  inputs.push_back(shifted);
  std::mt19937 gen(5);
  std::uniform_int_distribution<int> coordinate(0, 511);
  TetMesh scattered; // many co-spherical and co-planar groups, and duplicates
  for (int i = 0; i < 30000; ++i)
    scattered.addVertex(coordinate(gen) / 64 * 64, coordinate(gen) / 32 * 32, coordinate(gen));
  inputs.push_back(scattered);
  inputs.push_back(gridPoints(40)); // 64000 points: the last rounds go in halves
  for (const TetMesh& input : inputs)
  {
    TetMesh fast = input, general = input;
    DelaunayOptions options;
    options.validate = true;
    const DelaunayResult rf = buildDelaunay(fast, options);
    ASSERT_TRUE(rf.ok) << rf.error;
    options.smallLatticePredicates = false;
    options.validate = false;
    const DelaunayResult rg = buildDelaunay(general, options);
    ASSERT_TRUE(rg.ok) << rg.error;
    EXPECT_EQ(fast.tets, general.tets) << input.vertexCount() << " points";
    EXPECT_EQ(fast.neighbors, general.neighbors) << input.vertexCount() << " points";
    EXPECT_EQ(rf.duplicates, rg.duplicates);
  }
}

TEST(Delaunay, HullVolumeWithCubeCorners)
{
  // Random points inside [0,1]^3 plus the 8 corners: the convex hull is the unit cube.
  TetMesh mesh = randomPoints(30000, 21);
  for (int c = 0; c < 8; ++c)
    mesh.addVertex(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  DelaunayResult r;
  buildAndValidate(mesh, &r, true);
  EXPECT_NEAR(static_cast<double>(volumeWithoutVertices(mesh, r.firstBoxVertex)), 1.0, 1e-12);
}

TEST(Delaunay, HullVolumeOfRandomPointsMatchesGiftWrap)
{
  // Independent hull volume: brute-force hull facets (every triple with all points on one
  // side, exact orient3d) summed as cones from an interior point. Small n keeps it O(n^4)-ok.
  TetMesh mesh = randomPoints(60, 99);
  const VertexId n = mesh.vertexCount();
  std::vector<double> pts(mesh.coords);
  double centroid[3] = { 0, 0, 0 };
  for (VertexId v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k)
      centroid[k] += pts[3 * v + k] / n;
  long double hullVolume = 0;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
      {
        int pos = 0, neg = 0;
        for (int d = 0; d < n && !(pos && neg); ++d)
        {
          if (d == a || d == b || d == c)
            continue;
          int s = predicates::orient3d(&pts[3 * a], &pts[3 * b], &pts[3 * c], &pts[3 * d]);
          pos += s > 0;
          neg += s < 0;
        }
        if (pos && neg)
          continue;
        const double* p[3] = { &pts[3 * a], &pts[3 * b], &pts[3 * c] };
        long double m[3][3];
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k)
            m[r][k] = static_cast<long double>(p[r][k]) - centroid[k];
        long double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
          m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
          m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        hullVolume += std::fabs(det) / 6;
      }
  DelaunayResult r;
  buildAndValidate(mesh, &r, true);
  EXPECT_NEAR(static_cast<double>(volumeWithoutVertices(mesh, r.firstBoxVertex)),
    static_cast<double>(hullVolume),
    1e-12);
}

namespace
{

// The sorted vertex triples of all faces flagged constrained.
std::set<std::array<VertexId, 3>> constrainedFaces(const TetMesh& mesh)
{
  std::set<std::array<VertexId, 3>> faces;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (!mesh.isDeleted(t))
      for (int f = 0; f < 4; ++f)
        if (mesh.isConstrained(t, f))
        {
          std::array<VertexId, 3> v;
          for (int k = 0; k < 3; ++k)
            v[k] = mesh.vertex(t, kFaceVertices[f][k]);
          std::sort(v.begin(), v.end());
          faces.insert(v);
        }
  return faces;
}

} // namespace

TEST(Delaunay, InsertVertexRespectsConstrainedFaces)
{
  TetMesh mesh = randomPoints(2000, 123);
  DelaunayResult r = buildDelaunay(mesh);
  ASSERT_TRUE(r.ok);
  // Mark every 7th interior face as constrained on both sides.
  int marked = 0;
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = mesh.neighbor(t, f);
      if (n == kNoNeighbor || (t * 4 + f) % 7 != 0)
        continue;
      mesh.setConstrained(t, f, true);
      mesh.setConstrained(faceTet(n), faceIndex(n), true);
      ++marked;
    }
  ASSERT_GT(marked, 100);
  const auto before = constrainedFaces(mesh);

  InsertionWorkspace* ws = createInsertionWorkspace();
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> u(0, 1);
  TetId hint = 0;
  int inserted = 0;
  std::vector<VertexId> absent = r.duplicates;
  for (int i = 0; i < 3000; ++i)
  {
    const VertexId v = mesh.addVertex(u(gen), u(gen), u(gen));
    InsertResult ir = insertVertex(mesh, v, hint, *ws);
    if (ir.status == InsertStatus::Inserted)
    {
      ++inserted;
      hint = ir.tet;
    }
    else
    {
      absent.push_back(v);
    }
  }
  // A point exactly on a constrained face (its centroid rounded) may be refused, never
  // mangled: take exact midpoints of constrained face edges, which lie on the face boundary.
  int refused = 0;
  for (const auto& face : before)
  {
    if (refused >= 20)
      break;
    const double* a = mesh.point(face[0]);
    const double* b = mesh.point(face[1]);
    double m[3];
    for (int k = 0; k < 3; ++k)
      m[k] = (a[k] + b[k]) / 2; // rounded: keep only the midpoints exactly on the edge
    bool onEdge = true;
    for (int drop = 0; drop < 3; ++drop)
      onEdge = onEdge && predicates::orient2d(a, b, m, drop) == 0;
    if (!onEdge)
      continue;
    const VertexId v = mesh.addVertex(m[0], m[1], m[2]);
    InsertResult ir = insertVertex(mesh, v, hint, *ws);
    EXPECT_EQ(ir.status, InsertStatus::OnConstraint);
    absent.push_back(v);
    ++refused;
  }
  destroyInsertionWorkspace(ws);
  EXPECT_GT(inserted, 2900);
  EXPECT_EQ(checkOrientation(mesh), "");
  EXPECT_EQ(checkAdjacency(mesh, true), "");
  EXPECT_EQ(checkVerticesPresent(mesh, mesh.vertexCount(), absent), "");
  // Every constrained face is still there, still flagged; no scratch bits left behind.
  const auto after = constrainedFaces(mesh);
  for (const auto& f : before)
    EXPECT_TRUE(after.count(f)) << f[0] << " " << f[1] << " " << f[2];
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (!mesh.isDeleted(t))
    {
      EXPECT_EQ(mesh.flags[t] & 0xF0, 0);
    }
  }
  EXPECT_GT(refused, 5);
}

TEST(Delaunay, InsertVertexIntoDelaunayKeepsItDelaunay)
{
  // Without constraints the checked insertion is plain Bowyer-Watson: points on faces and
  // edges of a grid mesh (half-integer coordinates) must keep the mesh exactly Delaunay.
  TetMesh mesh = gridPoints(6);
  ASSERT_TRUE(buildDelaunay(mesh).ok);
  InsertionWorkspace* ws = createInsertionWorkspace();
  TetId hint = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
    {
      const VertexId v = mesh.addVertex(i + 0.5, j + 0.5, 2); // on grid faces
      InsertResult ir = insertVertex(mesh, v, hint, *ws);
      ASSERT_EQ(ir.status, InsertStatus::Inserted);
      hint = ir.tet;
      const VertexId w = mesh.addVertex(i + 0.5, j, 3); // on grid edges
      ir = insertVertex(mesh, w, hint, *ws);
      ASSERT_EQ(ir.status, InsertStatus::Inserted);
    }
  const VertexId dup = mesh.addVertex(1, 2, 3);
  InsertResult ir = insertVertex(mesh, dup, hint, *ws);
  EXPECT_EQ(ir.status, InsertStatus::Duplicate);
  EXPECT_EQ(ir.existing, 1 * 36 + 2 * 6 + 3);
  const VertexId outside = mesh.addVertex(1e6, 0, 0);
  EXPECT_EQ(insertVertex(mesh, outside, hint, *ws).status, InsertStatus::OutsideMesh);
  destroyInsertionWorkspace(ws);
  EXPECT_EQ(validateDelaunayMesh(mesh, mesh.vertexCount() - 2, {}), "");
  EXPECT_GE(locatePoint(mesh, mesh.point(3), 0), 0);
}

TEST(Delaunay, InsertVertexInNonConvexMesh)
{
  // Keep only the tets of a 5^3 grid mesh inside an L-shaped region (the exterior and a
  // notch removed, as after exterior removal), then insert points from a far hint: the walk
  // can run into the notch's hull faces and must still find the point.
  TetMesh mesh = gridPoints(5);
  DelaunayResult r = buildDelaunay(mesh);
  ASSERT_TRUE(r.ok);
  auto centroid = [&mesh](TetId t, int k)
  {
    double c = 0;
    for (int i = 0; i < 4; ++i)
      c += mesh.point(mesh.vertex(t, i))[k] / 4;
    return c;
  };
  std::vector<char> removed(static_cast<std::size_t>(mesh.tetCapacity()), 0);
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    bool box = false;
    for (int i = 0; i < 4; ++i)
      box = box || mesh.vertex(t, i) >= r.firstBoxVertex;
    removed[t] = box || (centroid(t, 0) > 2 && centroid(t, 1) > 2);
  }
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
  {
    if (!removed[t])
    {
      for (int f = 0; f < 4; ++f)
      {
        const FaceRef n = mesh.neighbor(t, f);
        if (n != kNoNeighbor && removed[faceTet(n)])
          mesh.setHull(t, f);
      }
    }
  }
  for (TetId t = 0; t < mesh.tetCapacity(); ++t)
    if (removed[t])
      mesh.deleteTet(t);
  ASSERT_EQ(checkAdjacency(mesh), "");
  TetId hint = -1;
  for (TetId t = 0; t < mesh.tetCapacity() && hint < 0; ++t)
    if (!mesh.isDeleted(t) && centroid(t, 0) < 1 && centroid(t, 1) > 3)
      hint = t;
  ASSERT_GE(hint, 0);
  InsertionWorkspace* ws = createInsertionWorkspace();
  const VertexId v = mesh.addVertex(3.3, 0.7, 2.2); // across the notch from the hint
  InsertResult ir = insertVertex(mesh, v, hint, *ws);
  EXPECT_EQ(ir.status, InsertStatus::Inserted);
  const VertexId inNotch = mesh.addVertex(3.5, 3.5, 2.5);
  EXPECT_EQ(insertVertex(mesh, inNotch, hint, *ws).status, InsertStatus::OutsideMesh);
  destroyInsertionWorkspace(ws);
  EXPECT_EQ(checkOrientation(mesh), "");
  EXPECT_EQ(checkAdjacency(mesh), "");
  EXPECT_EQ(locatePoint(mesh, mesh.point(inNotch), hint), -1);
  EXPECT_GE(locatePoint(mesh, mesh.point(v), hint), 0);
}

TEST(Delaunay, CoplanarAndCollinearInput)
{
  // Flat input: every point on z = 0 (random and on a 2D grid), and points on one line.
  TetMesh flat;
  std::mt19937_64 gen(8);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 3000; ++i)
    flat.addVertex(u(gen), u(gen), 0.0);
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j)
      flat.addVertex(2 + i, j, 0.0);
  buildAndValidate(flat);
  TetMesh line;
  for (int i = 0; i < 500; ++i)
    line.addVertex(0.5 * i, 0.25 * i, -0.125 * i);
  buildAndValidate(line);
}

namespace
{

// Exact predicates are invariant under exact scaling (no underflow or overflow), so the
// tets must be identical to those of the unscaled points.
void expectScalingGivesTheSameMesh(const TetMesh& base, std::initializer_list<int> exponents)
{
  TetMesh reference = base;
  ASSERT_TRUE(buildDelaunay(reference).ok);
  for (int exponent : exponents)
  {
    TetMesh scaled = base;
    for (double& c : scaled.coords)
      c = std::ldexp(c, exponent);
    DelaunayOptions options;
    options.validate = true;
    const DelaunayResult r = buildDelaunay(scaled, options);
    ASSERT_TRUE(r.ok) << "2^" << exponent << ": " << r.error;
    EXPECT_EQ(scaled.tets, reference.tets) << "2^" << exponent;
  }
}

} // namespace

TEST(Delaunay, ScalingByPowersOfTwoGivesTheSameMesh)
{
  expectScalingGivesTheSameMesh(randomPoints(5000, 31), { -60, 60 });
}

// The predicates are exact only within [kMinExactCoordinate, kMaxExactCoordinate] (and 0):
// inside, scaling by a power of two gives the identical mesh right up to both ends; outside,
// the points are refused by name. The 4 points below are the fuzzer's reduction of a surface
// whose mesh came out with inverted tets and broken adjacency (a coordinate of 7.8e143).
TEST(Delaunay, CoordinatesBeyondTheExactRangeAreRefused)
{
  // Points in [1, 2): scaled, every coordinate stays within the range.
  ASSERT_GE(std::ldexp(1.0, -132), predicates::kMinExactCoordinate);
  ASSERT_LE(std::ldexp(2.0, 165), predicates::kMaxExactCoordinate);
  expectScalingGivesTheSameMesh(randomPoints(3000, 5, 1.0, 2.0), { -132, 165 });

  TetMesh fuzzed;
  fuzzed.addVertex(0.081250000000000003, 0.42535000000000001, 0.25);
  fuzzed.addVertex(0.11405, 0.33729999999999999, 0.35099999999999998);
  fuzzed.addVertex(0.4113, 0.25285000000000002, -0.12995000000000001);
  fuzzed.addVertex(0.34410000000000002, 0.26284999999999997, 7.8043713757899806e+143);
  DelaunayResult r = buildDelaunay(fuzzed);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("vertex 3 has coordinate 7.80437137578998"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("scale the model down"), std::string::npos) << r.error;

  TetMesh tiny = randomPoints(10, 6, 1.0, 2.0);
  tiny.coords[3 * 7 + 1] = 1e-300;
  r = buildDelaunay(tiny);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("vertex 7 has coordinate 1e-300"), std::string::npos) << r.error;
  tiny.coords[3 * 7 + 1] = std::numeric_limits<double>::quiet_NaN();
  r = buildDelaunay(tiny);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("vertex 7 has a non-finite coordinate"), std::string::npos) << r.error;
  tiny.coords[3 * 7 + 1] = 0.0; // zero is exact at any scale
  EXPECT_TRUE(buildDelaunay(tiny).ok);
}

// The table-driven Hilbert keys must equal the textbook transpose algorithm (the insertion
// order, hence every tet id, depends on them): every point of the grids up to 2^6 per axis,
// then random points up to 21 bits.
TEST(Delaunay, HilbertKeysMatchTheTransposeAlgorithm)
{
  auto reference = [](std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits)
  {
    std::uint32_t axes[3] = { x, y, z };
    const std::uint32_t top = 1u << (bits - 1);
    for (std::uint32_t q = top; q > 1; q >>= 1)
      for (int i = 0; i < 3; ++i)
      {
        if (axes[i] & q)
          axes[0] ^= q - 1;
        else
        {
          const std::uint32_t t = (axes[0] ^ axes[i]) & (q - 1);
          axes[0] ^= t;
          axes[i] ^= t;
        }
      }
    for (int i = 1; i < 3; ++i)
      axes[i] ^= axes[i - 1];
    std::uint32_t t = 0;
    for (std::uint32_t q = top; q > 1; q >>= 1)
      if (axes[2] & q)
        t ^= q - 1;
    std::uint64_t key = 0;
    for (int b = bits - 1; b >= 0; --b)
      for (int i = 0; i < 3; ++i)
        key = (key << 1) | (((axes[i] ^ t) >> b) & 1u);
    return key;
  };
  for (int bits = 1; bits <= 6; ++bits)
    for (std::uint32_t x = 0; x < (1u << bits); ++x)
      for (std::uint32_t y = 0; y < (1u << bits); ++y)
        for (std::uint32_t z = 0; z < (1u << bits); ++z)
          ASSERT_EQ(hilbertIndex(x, y, z, bits), reference(x, y, z, bits)) << bits;
  std::mt19937 gen(7);
  for (int bits = 1; bits <= 21; ++bits)
  {
    const std::uint32_t mask = (1u << bits) - 1;
    for (int k = 0; k < 20000; ++k)
    {
      const std::uint32_t x = gen() & mask, y = gen() & mask, z = gen() & mask;
      ASSERT_EQ(hilbertIndex(x, y, z, bits), reference(x, y, z, bits)) << bits;
    }
  }
}
