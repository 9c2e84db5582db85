// refineInterior: interior points for a size field on meshes made by meshSurface. Measured:
// the share of interior edges whose length in units of h lies in [0.7, 1.42], the point count
// against the density estimate, and exact invariants (boundary faces = input triangles, no
// inverted tet, region volumes unchanged, no new vertex on the boundary), determinism.
#include "InteriorRefinement.h"
#include "MeshAssembly.h"
#include "MeshChecks.h"
#include "Mesher.h"
#include "Predicates.h"
#include "SurfaceGenerators.h"
#include "TetQuality.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <map>
#include <set>
#include <unordered_set>

using namespace tetmesher;
namespace tt = tetmesher::testing;
using tt::Surface;

namespace
{

struct Case
{
  Surface surface;
  MesherResult boundary;
  RegionMesh mesh;
};

bool prepare(Case& s)
{
  s.boundary = meshSurface(s.surface.points.data(),
    s.surface.pointCount(),
    s.surface.triangles.data(),
    s.surface.triangleCount());
  if (!s.boundary.ok)
    return false;
  return assembleRegionMesh(s.boundary.points, s.boundary.tets, s.boundary.regionIds, s.mesh);
}

// The refined mesh as a MesherResult, so that tt::checkMesh (exact, GMP) applies.
MesherResult asResult(const Case& s)
{
  MesherResult r;
  r.ok = true;
  extractRegionMesh(s.mesh, r.points, r.tets, r.regionIds);
  r.regionCount = s.boundary.regionCount;
  r.steinerPoints = static_cast<int>(r.points.size() / 3) - s.surface.pointCount();
  std::map<std::array<std::int32_t, 3>, std::int32_t> faces;
  for (std::size_t t = 0; t < r.tets.size() / 4; ++t)
    for (int f = 0; f < 4; ++f)
    {
      std::array<std::int32_t, 3> key;
      for (int k = 0; k < 3; ++k)
        key[k] = r.tets[4 * t + kFaceVertices[f][k]];
      std::sort(key.begin(), key.end());
      faces[key] = static_cast<std::int32_t>(4 * t + f);
    }
  for (std::int32_t t = 0; t < s.surface.triangleCount(); ++t)
  {
    std::array<std::int32_t, 3> key = {
      s.surface.triangles[3 * t], s.surface.triangles[3 * t + 1], s.surface.triangles[3 * t + 2]
    };
    std::sort(key.begin(), key.end());
    auto it = faces.find(key);
    r.boundaryFaceTet.push_back(it == faces.end() ? 0 : it->second);
  }
  return r;
}

struct EdgeStats
{
  std::size_t interior = 0;
  std::size_t inBand = 0;
  std::size_t tooShort = 0;
  std::size_t tooLong = 0;
  double meanLength = 0;
  double share() const { return interior ? double(inBand) / double(interior) : 0; }
};

// Interior edges (edges of no constrained face) and their length in units of h:
// l * (1/h_a + 1/h_b) / 2.
EdgeStats edgeStats(const RegionMesh& rm,
  const std::vector<double>& h,
  double lo = 0.7,
  double hi = 1.42)
{
  const TetMesh& m = rm.mesh;
  std::set<std::pair<VertexId, VertexId>> constrained, all;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        all.emplace(
          std::min(m.vertex(t, i), m.vertex(t, j)), std::max(m.vertex(t, i), m.vertex(t, j)));
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = m.neighbor(t, f);
      bool c = m.isConstrained(t, f) || n == kNoNeighbor || rm.region[t] != rm.region[faceTet(n)];
      if (!c)
        continue;
      for (int k = 0; k < 3; ++k)
      {
        VertexId a = m.vertex(t, kFaceVertices[f][k]),
                 b = m.vertex(t, kFaceVertices[f][(k + 1) % 3]);
        constrained.emplace(std::min(a, b), std::max(a, b));
      }
    }
  }
  EdgeStats s;
  for (const auto& e : all)
  {
    if (constrained.count(e))
      continue;
    const double* p = m.point(e.first);
    const double* q = m.point(e.second);
    const double l = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                       (p[2] - q[2]) * (p[2] - q[2])) *
      0.5 * (1 / h[e.first] + 1 / h[e.second]);
    ++s.interior;
    s.meanLength += l;
    if (l < lo)
      ++s.tooShort;
    else if (l > hi)
      ++s.tooLong;
    else
      ++s.inBand;
  }
  s.meanLength /= std::max<double>(1.0, double(s.interior));
  return s;
}

// Exact volume (x6) of each region.
std::vector<mpq_class> regionVolumes(const RegionMesh& rm)
{
  std::vector<mpq_class> v;
  const TetMesh& m = rm.mesh;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    const std::size_t r = static_cast<std::size_t>(rm.region[t]);
    if (v.size() <= r)
      v.resize(r + 1);
    v[r] += tt::det6(m.point(m.vertex(t, 3)),
      m.point(m.vertex(t, 0)),
      m.point(m.vertex(t, 1)),
      m.point(m.vertex(t, 2)));
  }
  return v;
}

std::string report(const char* name,
  const Case& s,
  const RefinementResult& r,
  const EdgeStats& e,
  double expectedPoints)
{
  char buffer[512];
  std::snprintf(buffer,
    sizeof buffer,
    "[%s] +%d points in %d rounds, %.3f s, %d tets (%.0f tets/s); interior edges in "
    "[0.7,1.42]h: %.2f%% (short %.2f%%, long %.2f%%) of %zu; interior points %d vs estimate "
    "%.0f "
    "(ratio %.3f); mean edge %.3f h; rejected near vertex %d, near boundary %d, kernel %d; lattice "
    "points %d\n",
    name,
    r.insertedPoints,
    r.rounds,
    r.seconds,
    s.mesh.mesh.liveTetCount(),
    s.mesh.mesh.liveTetCount() / std::max(r.seconds, 1e-9),
    100 * e.share(),
    100.0 * e.tooShort / std::max<std::size_t>(e.interior, 1),
    100.0 * e.tooLong / std::max<std::size_t>(e.interior, 1),
    e.interior,
    s.mesh.mesh.vertexCount() - s.surface.pointCount(),
    expectedPoints,
    (s.mesh.mesh.vertexCount() - s.surface.pointCount()) / expectedPoints,
    e.meanLength,
    r.rejectedNearVertex,
    r.rejectedNearBoundary,
    r.rejectedByKernel,
    r.latticePoints);
  std::printf("%s", buffer);
  // Shape of the result, for the optimisation stage that follows (not asserted here).
  std::vector<TetShape> shapes;
  const TetMesh& m = s.mesh.mesh;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
    if (!m.isDeleted(t)) // TetMesh's positive order is VTK's negative one: swap two vertices
      shapes.push_back(measureTet(m.point(m.vertex(t, 1)),
        m.point(m.vertex(t, 0)),
        m.point(m.vertex(t, 2)),
        m.point(m.vertex(t, 3))));
  const QualitySummary q = summarizeQuality(shapes);
  std::printf(
    "    quality: mean %.3f, min %.4f, Q<0.1 %.2f%%, Q<0.3 %.2f%%, dihedral %.1f..%.1f deg\n",
    q.mean,
    q.minimum,
    100 * q.shareBelow01,
    100 * q.shareBelow03,
    q.minDihedral,
    q.maxDihedral);
  return buffer;
}

// Share of tets with Q < 0.3.
double shareBelow03(const RegionMesh& rm)
{
  std::vector<TetShape> shapes;
  const TetMesh& m = rm.mesh;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
    if (!m.isDeleted(t))
      shapes.push_back(measureTet(m.point(m.vertex(t, 1)),
        m.point(m.vertex(t, 0)),
        m.point(m.vertex(t, 2)),
        m.point(m.vertex(t, 3))));
  return summarizeQuality(shapes).shareBelow03;
}

// Exact checks of a refined mesh: testing::checkMesh on its flat arrays (every tet positive by
// GMP, boundary faces = input triangles both ways, no non-input vertex on an input triangle,
// total volume = enclosed volume), plus symmetric adjacency, constraint flags on every boundary
// and interface face, region volumes unchanged, one positive size per vertex.
std::string checkRefined(const Case& s,
  const std::vector<double>& h,
  const std::vector<mpq_class>& volumesBefore,
  const std::vector<int>& sign)
{
  const TetMesh& m = s.mesh.mesh;
  if (h.size() != static_cast<std::size_t>(m.vertexCount()))
    return "vertexSize has " + std::to_string(h.size()) + " entries for " +
      std::to_string(m.vertexCount()) + " vertices";
  for (double x : h)
    if (!(x > 0) || !std::isfinite(x))
      return "a size is not positive";
  if (s.mesh.region.size() < static_cast<std::size_t>(m.tetCapacity()))
    return "region array too short";
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    for (int f = 0; f < 4; ++f)
    {
      const FaceRef n = m.neighbor(t, f);
      if (n == kNoNeighbor)
      {
        if (!m.isConstrained(t, f))
          return "a hull face is not constrained";
        continue;
      }
      if (m.isDeleted(faceTet(n)) || m.neighbor(faceTet(n), faceIndex(n)) != makeFaceRef(t, f))
        return "adjacency is not symmetric";
      const bool interface = s.mesh.region[t] != s.mesh.region[faceTet(n)];
      if (interface != m.isConstrained(t, f))
        return "constraint flag differs from the region interface";
    }
  }
  if (regionVolumes(s.mesh) != volumesBefore)
    return "region volumes changed";
  return tt::checkMesh(s.surface, asResult(s), sign, s.boundary.regionCount);
}

// Worst violation of the gradation over the mesh edges: max of (h_j - h_i) / ((g-1) l_ij).
double gradationExcess(const TetMesh& m, const std::vector<double>& h, double g)
{
  double worst = 0;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
      {
        const VertexId a = m.vertex(t, i), b = m.vertex(t, j);
        const double* p = m.point(a);
        const double* q = m.point(b);
        const double l = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
          (p[2] - q[2]) * (p[2] - q[2]));
        worst = std::max(worst, std::fabs(h[a] - h[b]) / ((g - 1) * l));
      }
  }
  return worst;
}

// Point count estimate. A vertex of a mesh whose edges all have length h, packed as densely as
// the face-centred cubic lattice (the tet-octahedron honeycomb: per vertex 2 regular tets and
// an octahedron = 6 regular tets), owns a volume 6 * h^3 / (6 sqrt 2) = h^3 / sqrt 2; a
// boundary vertex owns about half of that. So the interior vertices number about
//   N_fcc = integral of sqrt(2) / h^3 dV  -  N_boundary / 2.
// A Delaunay mesh whose edges are spread over [0.7, 1.42] h (mean ~1.03 h) is denser than the
// lattice: there are ~6.1 tets per vertex (the lattice: 6 regular-tet volumes) and they are
// not regular (mean Q ~0.65; mean volume ~0.8 of the regular tet of edge h), so a vertex owns
// about 6 / (6.1 * 0.8) ~ 1 / 1.2 of the lattice's volume. kDensity = 1.25 is that empirical
// factor: 1.21 on the unit cube at h = 1/33 (where the boundary correction matters least);
// the shapes below give 0.87 .. 1.19 times 1.25 x N_fcc, checked within 20%.
constexpr double kDensity = 1.25;

double fccInteriorEstimate(const RegionMesh& rm,
  const std::vector<double>& h,
  std::int32_t boundaryPoints)
{
  const TetMesh& m = rm.mesh;
  double sum = 0;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    double inv3 = 0;
    for (int i = 0; i < 4; ++i)
      inv3 += 0.25 / (h[m.vertex(t, i)] * h[m.vertex(t, i)] * h[m.vertex(t, i)]);
    const double vol = tt::det6(m.point(m.vertex(t, 3)),
                         m.point(m.vertex(t, 0)),
                         m.point(m.vertex(t, 1)),
                         m.point(m.vertex(t, 2)))
                         .get_d() /
      6;
    sum += vol * std::sqrt(2.0) * inv3;
  }
  return sum - boundaryPoints / 2.0;
}

// Two boxes [0,1]^3 and [1,2]x[0,1]^2 with n cells per side, sharing the face x = 1 (listed
// once): two regions. sign: +1 for outer triangles, 0 for the shared ones.
// Triangle t of `part` in `s`, its points merged with s's by their coordinates (ids).
std::array<std::int32_t, 3> mergedTriangle(Surface& s,
  std::map<std::array<double, 3>, std::int32_t>& ids,
  const Surface& part,
  std::int32_t t)
{
  std::array<std::int32_t, 3> v;
  for (int k = 0; k < 3; ++k)
  {
    const double* p = &part.points[3 * part.triangles[3 * t + k]];
    auto [it, fresh] = ids.emplace(std::array<double, 3>{ p[0], p[1], p[2] }, s.pointCount());
    if (fresh)
      s.addPoint(p[0], p[1], p[2]);
    v[k] = it->second;
  }
  return v;
}

Surface twoBoxes(int n, std::vector<int>& sign)
{
  Surface a = tt::box({ 0, 0, 0 }, { 1, 1, 1 }, { n, n, n }, false);
  Surface b = tt::box({ 1, 0, 0 }, { 2, 1, 1 }, { n, n, n }, false);
  Surface s;
  std::map<std::array<double, 3>, std::int32_t> ids;
  std::map<std::array<std::int32_t, 3>, std::int32_t> seen;
  sign.clear();
  for (const Surface* part : { &a, &b })
  {
    for (std::int32_t t = 0; t < part->triangleCount(); ++t)
    {
      const std::array<std::int32_t, 3> v = mergedTriangle(s, ids, *part, t);
      std::array<std::int32_t, 3> key = v;
      std::sort(key.begin(), key.end());
      auto found = seen.find(key);
      if (found != seen.end())
      {
        sign[found->second] = 0;
        continue;
      }
      seen.emplace(key, s.triangleCount());
      s.addTriangle(v[0], v[1], v[2]);
      sign.push_back(1);
    }
  }
  return s;
}

// The unit sphere meshed as a level-`level` icosphere and then inverted in the sphere centred
// at (d,0,0) with radius^2 = d^2 - 1, which is orthogonal to the unit sphere: the sphere maps
// onto itself, triangles keep their shapes (inversion is conformal) and are scaled by
// (d^2 - 1) / |x - c|^2, so edge lengths vary by ((d+1)/(d-1))^2 = 10 for d = 1.925.
Surface invertedSphere(int level, double d = 1.925)
{
  Surface s = tt::icosphere(level);
  const double r2 = d * d - 1;
  for (std::int32_t v = 0; v < s.pointCount(); ++v)
  {
    double* p = &s.points[3 * v];
    const double x = p[0] - d, y = p[1], z = p[2];
    const double q = r2 / (x * x + y * y + z * z);
    p[0] = d + q * x;
    p[1] = q * y;
    p[2] = q * z;
  }
  const double origin[3] = { 0, 0, 0 };
  for (std::int32_t t = 0; t < s.triangleCount(); ++t)
    tt::orientAway(s, t, origin);
  return s;
}

} // namespace

TEST(InteriorRefinement, UnitCubeConstantSize)
{
  Case s;
  s.surface = tt::cube(10); // boundary edges 0.1 (and face diagonals)
  ASSERT_TRUE(prepare(s));
  const auto before = regionVolumes(s.mesh);
  std::vector<double> h(static_cast<std::size_t>(s.surface.pointCount()), 0.1);
  RefinementResult r = refineInterior(s.mesh, h, RefinementOptions{});
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_FALSE(r.budgetReached);
  EXPECT_GT(r.insertedPoints, 0);
  const EdgeStats e = edgeStats(s.mesh, h);
  const double fcc = std::sqrt(2.0) / (0.1 * 0.1 * 0.1) - s.surface.pointCount() / 2.0;
  const double interior = s.mesh.mesh.vertexCount() - s.surface.pointCount();
  report("cube h=0.1", s, r, e, kDensity * fcc);
  EXPECT_GE(e.share(), 0.95);
  EXPECT_NEAR(interior / (kDensity * fcc), 1.0, 0.2);
  std::vector<int> sign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
  EXPECT_EQ(checkRefined(s, h, before, sign), "");
  // Constant h stays constant (interpolation of equal sizes, gradation has nothing to do).
  for (double x : h)
    ASSERT_EQ(x, 0.1);
}

TEST(InteriorRefinement, DefaultSizesOnIcosphere)
{
  Case s;
  s.surface = tt::icosphere(3); // 642 points, edges ~0.16
  ASSERT_TRUE(prepare(s));
  const auto before = regionVolumes(s.mesh);
  std::vector<double> h = boundaryEdgeSizes(s.surface.points.data(),
    s.surface.pointCount(),
    s.surface.triangles.data(),
    s.surface.triangleCount());
  RefinementResult r = refineInterior(s.mesh, h, RefinementOptions{});
  ASSERT_TRUE(r.ok) << r.error;
  const EdgeStats e = edgeStats(s.mesh, h);
  const double estimate = kDensity * fccInteriorEstimate(s.mesh, h, s.surface.pointCount());
  report("icosphere default h", s, r, e, estimate);
  EXPECT_GE(e.share(), 0.95);
  EXPECT_NEAR((s.mesh.mesh.vertexCount() - s.surface.pointCount()) / estimate, 1.0, 0.2);
  std::vector<int> sign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
  EXPECT_EQ(checkRefined(s, h, before, sign), "");
}

TEST(InteriorRefinement, TwoRegionsKeepTheirVolumesAndInterface)
{
  Case s;
  std::vector<int> sign;
  s.surface = twoBoxes(8, sign);
  ASSERT_TRUE(prepare(s));
  ASSERT_EQ(s.boundary.regionCount, 2);
  const auto before = regionVolumes(s.mesh);
  ASSERT_EQ(before.size(), 2u);
  std::vector<double> h(static_cast<std::size_t>(s.surface.pointCount()), 0.125);
  RefinementResult r = refineInterior(s.mesh, h, RefinementOptions{});
  ASSERT_TRUE(r.ok) << r.error;
  const EdgeStats e = edgeStats(s.mesh, h);
  const double estimate = kDensity * fccInteriorEstimate(s.mesh, h, s.surface.pointCount());
  report("two boxes h=0.125", s, r, e, estimate);
  EXPECT_GE(e.share(), 0.95);
  EXPECT_EQ(checkRefined(s, h, before, sign), "");
  // Every new vertex lies strictly inside one box: its tets all have the same region, the
  // one whose side of x = 1 it is on.
  const TetMesh& m = s.mesh.mesh;
  std::vector<int> side(static_cast<std::size_t>(m.vertexCount()), -1);
  int mixed = 0;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    for (int i = 0; i < 4; ++i)
    {
      const VertexId v = m.vertex(t, i);
      if (v < s.surface.pointCount())
        continue;
      if (side[v] == -1)
        side[v] = s.mesh.region[t];
      mixed += side[v] != s.mesh.region[t];
      EXPECT_NE(m.point(v)[0], 1.0);
    }
  }
  EXPECT_EQ(mixed, 0);
}

TEST(InteriorRefinement, CoarseBoundaryFineSize)
{
  // 12 triangles (edges 1 and 1.41), h = 0.04: the boundary stays the 12 triangles, the floor
  // next to them (maxFloorRatio h = 0.16 at the faces, falling by 0.8 (g - 1) = 0.4 per unit
  // of depth) grades the sizes down to h at depth 0.3, and the core is meshed at h.
  Case s;
  s.surface = tt::cube(1);
  ASSERT_TRUE(prepare(s));
  const auto before = regionVolumes(s.mesh);
  const double h0 = 0.04;
  std::vector<double> h(8, h0);
  const RefinementOptions options;
  const double slope = options.floorSlope * (options.size.gradation - 1);
  const double atFace = options.maxFloorRatio * h0;
  const double reach = (atFace - h0) / slope;
  const double deepFrom = reach + h0;
  RefinementResult r = refineInterior(s.mesh, h, options);
  ASSERT_TRUE(r.ok) << r.error;
  const EdgeStats e = edgeStats(s.mesh, h);
  report("12-triangle cube h=0.04", s, r, e, 0);
  std::vector<int> sign(12, 1);
  EXPECT_EQ(checkRefined(s, h, before, sign), "");
  const TetMesh& m = s.mesh.mesh;
  auto depth = [](const double* p)
  {
    double d = 1;
    for (int k = 0; k < 3; ++k)
      d = std::min({ d, p[k], 1 - p[k] });
    return d;
  };
  // The sizes used: never under the floor (every face has the capped size, and the distance
  // to the nearest face is the depth), never over the cap.
  for (VertexId v = 8; v < m.vertexCount(); ++v)
  {
    const double floor = std::max(h0, atFace - slope * depth(m.point(v)));
    ASSERT_GE(h[v], floor * (1 - 1e-12)) << "vertex " << v;
    ASSERT_LE(h[v], atFace * (1 + 1e-12)) << "vertex " << v;
  }
  // Edges between interior points, in the sizes used; and those at least deepFrom deep, in
  // h0 (the floor does not reach them).
  std::size_t inner = 0, band = 0, deep = 0, deepBand = 0;
  std::set<std::pair<VertexId, VertexId>> seen;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
      {
        VertexId a = std::min(m.vertex(t, i), m.vertex(t, j));
        VertexId b = std::max(m.vertex(t, i), m.vertex(t, j));
        if (a < 8 || !seen.emplace(a, b).second)
          continue;
        const double* p = m.point(a);
        const double* q = m.point(b);
        const double length = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) +
          (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
        const double l = length * 0.5 * (1 / h[a] + 1 / h[b]);
        ++inner;
        band += l >= 0.7 && l <= 1.42;
        if (depth(p) >= deepFrom && depth(q) >= deepFrom)
        {
          ++deep;
          deepBand += length / h0 >= 0.7 && length / h0 <= 1.42;
        }
      }
  }
  std::printf("[12-triangle cube] in band: %.2f%% of %zu edges between interior points (in the "
              "sizes used), %.2f%% of %zu edges at least %g deep (in h)\n",
    100.0 * band / inner,
    inner,
    100.0 * deepBand / deep,
    deep,
    deepFrom);
  EXPECT_GT(deep, 1000u);
  EXPECT_GE(double(band) / inner, 0.9);
  EXPECT_GE(double(deepBand) / deep, 0.95);
}

TEST(InteriorRefinement, PointsKeepOffFacesLargerThanH)
{
  // cube(4) at h = 1/12: faces with legs of 3 h and a diagonal of 4.24 h. The floor gives a
  // point at depth d a size of at least F - slope d, F >= 0.25 - (maxEdgeRatio - 1) h (the
  // mean boundary edge at every vertex is at least a leg), and the edge splitting keeps
  // points 0.5 of their size off the faces: d >= 0.5 (F - slope d), so the tet on each face is
  // tall. Without the floor a split point at 0.5 h, 0.12 of the diagonal, is an apex.
  Case s;
  s.surface = tt::cube(4);
  ASSERT_TRUE(prepare(s));
  const auto before = regionVolumes(s.mesh);
  const double h0 = 1.0 / 12;
  std::vector<double> h(static_cast<std::size_t>(s.surface.pointCount()), h0);
  const RefinementOptions options;
  RefinementResult r = refineInterior(s.mesh, h, options);
  ASSERT_TRUE(r.ok) << r.error;
  std::vector<int> sign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
  EXPECT_EQ(checkRefined(s, h, before, sign), "");
  const TetMesh& m = s.mesh.mesh;
  const VertexId surfacePoints = s.surface.pointCount();
  ASSERT_GT(m.vertexCount(), surfacePoints + 50);
  const double diagonal = std::sqrt(2.0) / 4;
  const double atFace =
    std::min(0.25 - (options.maxEdgeRatio - 1) * h0, options.maxFloorRatio * h0);
  const double slope = options.floorSlope * (options.size.gradation - 1);
  const double splitClearance =
    options.minBoundaryDistance * atFace / (1 + options.minBoundaryDistance * slope);
  double nearest = 1e300;
  for (VertexId v = surfacePoints; v < m.vertexCount(); ++v)
    for (int k = 0; k < 3; ++k)
      nearest = std::min({ nearest, m.point(v)[k], 1 - m.point(v)[k] });
  // Every face of the cube(4) surface has the same diagonal, so the distance to the cube's
  // boundary is the distance to the nearest face.
  EXPECT_GE(nearest, splitClearance * (1 - 1e-12));
  double lowestApex = 1e300;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
  {
    if (m.isDeleted(t))
      continue;
    for (int f = 0; f < 4; ++f)
    {
      VertexId boundaryCorners = 0;
      for (int k = 0; k < 3; ++k)
        boundaryCorners += m.vertex(t, kFaceVertices[f][k]) < surfacePoints;
      const VertexId apex = m.vertex(t, f);
      if (boundaryCorners < 3 || apex < surfacePoints)
        continue;
      const double* p = m.point(apex);
      // The face lies in a cube face, so its plane is the nearest axis plane of its centroid.
      double c[3] = { 0, 0, 0 };
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a)
          c[a] += m.point(m.vertex(t, kFaceVertices[f][k]))[a] / 3;
      for (int a = 0; a < 3; ++a)
        if (c[a] < 1e-12 || c[a] > 1 - 1e-12)
          lowestApex = std::min(lowestApex, std::fabs(p[a] - c[a]));
    }
  }
  std::printf("[cube(4), h = 1/12] nearest interior point to the boundary %.4f (%.2f of a face's "
              "diagonal); lowest apex over a boundary face %.4f (%.2f)\n",
    nearest,
    nearest / diagonal,
    lowestApex,
    lowestApex / diagonal);
  EXPECT_GE(lowestApex, splitClearance * (1 - 1e-12));
}

TEST(InteriorRefinement, SizeVaryingTenfoldAcrossTheSurface)
{
  Case s;
  s.surface = invertedSphere(3);
  ASSERT_TRUE(prepare(s));
  const auto before = regionVolumes(s.mesh);
  std::vector<double> h = boundaryEdgeSizes(s.surface.points.data(),
    s.surface.pointCount(),
    s.surface.triangles.data(),
    s.surface.triangleCount());
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  std::printf("[inverted sphere] surface sizes %.4f .. %.4f (ratio %.1f)\n", *lo, *hi, *hi / *lo);
  ASSERT_GE(*hi / *lo, 8.0);
  RefinementOptions options;
  RefinementResult r = refineInterior(s.mesh, h, options);
  ASSERT_TRUE(r.ok) << r.error;
  const EdgeStats e = edgeStats(s.mesh, h);
  const double estimate = kDensity * fccInteriorEstimate(s.mesh, h, s.surface.pointCount());
  report("inverted sphere, h x10", s, r, e, estimate);
  EXPECT_GE(e.share(), 0.95);
  EXPECT_NEAR((s.mesh.mesh.vertexCount() - s.surface.pointCount()) / estimate, 1.0, 0.2);
  const double excess = gradationExcess(s.mesh.mesh, h, options.size.gradation);
  std::printf("[inverted sphere] gradation: max |h_i - h_j| / ((g-1) l_ij) = %.6f\n", excess);
  EXPECT_LE(excess, 1 + 1e-9);
  std::vector<int> sign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
  EXPECT_EQ(checkRefined(s, h, before, sign), "");
}

// The proximity test keeps a size class's cells in arrays or in hash tables: the answers, hence
// the mesh, are the same. And no new vertex is nearer another vertex than minPointDistance in
// units of h (by brute force over every pair), through both the shared grid and the halves'
// own ones (halves from 256 points here), in sizes of several classes (h varies 10x).
TEST(InteriorRefinement, ProximityGridsAgreeAndKeepNewPointsApart)
{
  Case s[2];
  std::vector<double> h[2];
  VertexId initial = 0;
  RefinementOptions options;
  options.halvesMinPoints = 256;
  for (int k = 0; k < 2; ++k)
  {
    s[k].surface = invertedSphere(3);
    ASSERT_TRUE(prepare(s[k]));
    initial = s[k].mesh.mesh.vertexCount();
    h[k] = boundaryEdgeSizes(s[k].surface.points.data(),
      s[k].surface.pointCount(),
      s[k].surface.triangles.data(),
      s[k].surface.triangleCount());
    options.proximityCellArrays = k == 0;
    const RefinementResult r = refineInterior(s[k].mesh, h[k], options);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_GT(r.latticeHalvesPoints + r.splitHalvesPoints, 0);
    EXPECT_GT(r.rejectedNearVertex, 0); // the test refused points: it decided something
  }
  const TetMesh& m = s[0].mesh.mesh;
  ASSERT_GT(m.vertexCount(), initial);
  EXPECT_TRUE(m.coords == s[1].mesh.mesh.coords) << "the points differ";
  EXPECT_TRUE(m.tets == s[1].mesh.mesh.tets) << "the tets differ";
  EXPECT_TRUE(h[0] == h[1]) << "the sizes differ";
  double closest = std::numeric_limits<double>::infinity();
  for (VertexId b = initial; b < m.vertexCount(); ++b)
    for (VertexId a = 0; a < b; ++a)
    {
      const double* p = m.point(a);
      const double* q = m.point(b);
      const double d = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
        (p[2] - q[2]) * (p[2] - q[2]));
      closest = std::min(closest, d * 0.5 * (1 / h[0][a] + 1 / h[0][b]));
    }
  std::printf("[proximity] %d new vertices, the nearest pair %.4f h apart (at least %.2f)\n",
    m.vertexCount() - initial,
    closest,
    options.minPointDistance);
  EXPECT_GE(closest, options.minPointDistance * (1 - 1e-12));
}

TEST(InteriorRefinement, LatticeOnCosphericalUvSphere)
{
  // Issue 7: every point of a latitude-longitude sphere lies on one sphere, so every tet of
  // the boundary mesh has that sphere as circumsphere, and its pole fans make the default h
  // vary ~16x. The lattice prefill used to insert its points in one Hilbert sweep, whose front
  // conflicted with all the not yet refined tets (cavities of thousands of tets, shrunk to
  // stars that left long edges no split could fix): 9x the CPU time of edge splitting alone
  // here and 81% of interior edges in [0.7, 1.42] h; ~30x on Data/uv_sphere.vtp (100 x 100).
  // In BRIO order: under 2x and 96%. The times are printed, not asserted (noisy machines);
  // the share of edges in band is what fails on the old order.
  struct Run
  {
    RefinementResult result;
    double cpu = 0;
    double share = 0;
    std::string check;
  };
  auto run = [](double latticeSpacing, bool check)
  {
    Run out;
    Case s;
    s.surface = tt::uvSphere(60, 60);
    if (!prepare(s))
      return out;
    const auto before = regionVolumes(s.mesh);
    std::vector<double> h = boundaryEdgeSizes(s.surface.points.data(),
      s.surface.pointCount(),
      s.surface.triangles.data(),
      s.surface.triangleCount());
    RefinementOptions options;
    options.latticeSpacing = latticeSpacing;
    const std::clock_t cpu0 = std::clock();
    out.result = refineInterior(s.mesh, h, options);
    out.cpu = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
    const EdgeStats e = edgeStats(s.mesh, h);
    out.share = e.share();
    report(latticeSpacing > 0 ? "uv sphere 60x60, lattice" : "uv sphere 60x60, no lattice",
      s,
      out.result,
      e,
      kDensity * fccInteriorEstimate(s.mesh, h, s.surface.pointCount()));
    if (check)
    {
      std::vector<int> sign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
      out.check = checkRefined(s, h, before, sign);
    }
    return out;
  };
  const Run lattice = run(RefinementOptions{}.latticeSpacing, true);
  const Run split = run(0, false);
  ASSERT_TRUE(lattice.result.ok) << lattice.result.error;
  ASSERT_TRUE(split.result.ok) << split.result.error;
  std::printf("[uv sphere 60x60] refinement CPU: %.3f s with the lattice, %.3f s without\n",
    lattice.cpu,
    split.cpu);
  EXPECT_GT(lattice.result.latticePoints, lattice.result.insertedPoints / 2);
  // The share moves by +-1.5% with any small change upstream or in the lattice's levels (on
  // the same boundary mesh: 94.9% at the default level ratio 1.19, 96.4% at 1.15, 96.6% at
  // 1.25; 93.4-95.9% over three boundary recoveries of this sphere, 92.9% after recovery's
  // first sweep went by edges alone), so the bound sits below that spread and far above the
  // sweep order's 81%. The 95% goal of issue 7 is checked on constant and varying h elsewhere
  // in this file.
  EXPECT_GE(lattice.share, 0.92);
  EXPECT_EQ(lattice.check, "");
}

TEST(InteriorRefinement, GradationSmoothsAJump)
{
  // Sizes 0.05 on the faces x = 0 side's vertices (x < 0.05), 0.5 elsewhere: the gradation
  // must lower the others so that h grows by at most (g - 1) per unit length along edges.
  Case s;
  s.surface = tt::cube(10);
  ASSERT_TRUE(prepare(s));
  const auto before = regionVolumes(s.mesh);
  std::vector<double> h(static_cast<std::size_t>(s.surface.pointCount()));
  for (std::int32_t v = 0; v < s.surface.pointCount(); ++v)
    h[v] = s.surface.points[3 * v] < 0.05 ? 0.05 : 0.5;
  RefinementOptions options;
  options.size.gradation = 1.3;
  // The surface's edges (0.1) are twice the sizes asked for next to x = 0: the floor would
  // raise them; this test is about the gradation of the given sizes alone.
  options.maxFloorRatio = 0;
  RefinementResult r = refineInterior(s.mesh, h, options);
  ASSERT_TRUE(r.ok) << r.error;
  const double excess = gradationExcess(s.mesh.mesh, h, options.size.gradation);
  const EdgeStats e = edgeStats(s.mesh, h);
  report("cube, jump 0.05 | 0.5, g=1.3", s, r, e, 0);
  std::printf("[jump] gradation: max |h_i - h_j| / ((g-1) l_ij) = %.6f\n", excess);
  EXPECT_LE(excess, 1 + 1e-9);
  // The boundary vertices next to x = 0 were lowered (at x = 0.1: at most 0.05 + 0.3*0.1).
  for (std::int32_t v = 0; v < s.surface.pointCount(); ++v)
  {
    if (std::fabs(s.surface.points[3 * v] - 0.1) < 1e-12)
    {
      EXPECT_LE(h[v], 0.05 + 0.3 * 0.1 + 1e-12);
    }
  }
  std::vector<int> sign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
  EXPECT_EQ(checkRefined(s, h, before, sign), "");
}

// Two unit boxes that touch at the corner (1,1,1) only: the domain is pinched there (the
// corner's tets are two stars).
Surface boxesTouchingAtACorner(int n)
{
  Surface a = tt::box({ 0, 0, 0 }, { 1, 1, 1 }, { n, n, n });
  Surface b = tt::box({ 1, 1, 1 }, { 2, 2, 2 }, { n, n, n });
  Surface s;
  std::map<std::array<double, 3>, std::int32_t> ids;
  for (const Surface* part : { &a, &b })
    for (std::int32_t t = 0; t < part->triangleCount(); ++t)
    {
      const std::array<std::int32_t, 3> v = mergedTriangle(s, ids, *part, t);
      s.addTriangle(v[0], v[1], v[2]);
    }
  return s;
}

// Rounds that take their edges from the stars of the vertices changed since (starRoundRatio)
// make the mesh of rounds that take them from a graph of every edge: the same points, tets,
// and sizes. A graded jump, sizes varying tenfold with rounds in halves, no gradation at all,
// and a pinched domain (whose corner star, if walked, sends the rounds back to the graph).
TEST(InteriorRefinement, StarRoundsGiveTheGraphRoundsMesh)
{
  struct Setup
  {
    const char* name;
    Surface surface;
    double gradation;
    bool jump; // sizes jump: tenfold across x = 0.05, or next to the corner (1,1,1)
    bool corner = false;
  };
  std::vector<Setup> setups;
  setups.push_back({ "cube, jump", tt::cube(10), 1.3, true });
  setups.push_back({ "inverted sphere", invertedSphere(3), 1.5, false });
  setups.push_back({ "torus, no gradation", tt::torus(1.0, 0.35, 36, 14), 1.0, false });
  setups.push_back({ "boxes touching at a corner", boxesTouchingAtACorner(4), 1.5, true, true });
  for (Setup& setup : setups)
  {
    Case s[2];
    std::vector<double> h[2];
    RefinementResult r[2];
    for (int k = 0; k < 2; ++k)
    {
      s[k].surface = setup.surface;
      ASSERT_TRUE(prepare(s[k])) << setup.name;
      h[k] = boundaryEdgeSizes(s[k].surface.points.data(),
        s[k].surface.pointCount(),
        s[k].surface.triangles.data(),
        s[k].surface.triangleCount());
      if (setup.jump)
        for (std::int32_t v = 0; v < s[k].surface.pointCount(); ++v)
        {
          const double* p = &s[k].surface.points[3 * static_cast<std::size_t>(v)];
          h[k][v] = setup.corner
            ? (std::fabs(p[0] - 1) + std::fabs(p[1] - 1) + std::fabs(p[2] - 1) < 0.6 ? 0.04 : 0.3)
            : (p[0] < 0.05 ? 0.03 : 0.25);
        }
      RefinementOptions options;
      options.size.gradation = setup.gradation;
      options.maxFloorRatio = setup.jump ? 0 : options.maxFloorRatio;
      options.halvesMinPoints = 256;
      options.starRoundRatio = k == 0 ? 0 : 1e-9; // never, and whenever a round can
      r[k] = refineInterior(s[k].mesh, h[k], options);
      ASSERT_TRUE(r[k].ok) << setup.name << ": " << r[k].error;
    }
    std::printf("[stars] %s: %d rounds, %d from stars%s, %d points\n",
      setup.name,
      r[1].rounds,
      r[1].starRounds,
      r[1].starsRefused ? " (then refused)" : "",
      r[1].insertedPoints);
    EXPECT_EQ(r[0].starRounds, 0) << setup.name;
    EXPECT_GT(r[1].starRounds + (r[1].starsRefused ? 1 : 0), 0) << setup.name;
    EXPECT_EQ(r[0].rounds, r[1].rounds) << setup.name;
    EXPECT_TRUE(s[0].mesh.mesh.coords == s[1].mesh.mesh.coords) << setup.name << ": the points";
    EXPECT_TRUE(s[0].mesh.mesh.tets == s[1].mesh.mesh.tets) << setup.name << ": the tets";
    EXPECT_TRUE(h[0] == h[1]) << setup.name << ": the sizes";
  }
}

TEST(InteriorRefinement, BackgroundFieldOverridesInterpolation)
{
  Case s;
  s.surface = tt::icosphere(3);
  ASSERT_TRUE(prepare(s));
  const auto before = regionVolumes(s.mesh);
  auto field = [](const double* p) { return 0.1 + 0.05 * p[0]; }; // 0.05 .. 0.15
  std::vector<double> h; // no sizes given: all from the background
  RefinementOptions options;
  options.size.gradation = 0; // off, so new sizes are exactly the field's
  options.size.scale = 2;
  options.size.maxSize = 0.25;
  RefinementResult r = refineInterior(s.mesh, h, options, field);
  ASSERT_TRUE(r.ok) << r.error;
  const TetMesh& m = s.mesh.mesh;
  ASSERT_EQ(h.size(), static_cast<std::size_t>(m.vertexCount()));
  for (VertexId v = 0; v < m.vertexCount(); ++v)
    ASSERT_EQ(h[v], std::min(0.25, 2 * field(m.point(v)))) << v;
  const EdgeStats e = edgeStats(s.mesh, h);
  report("icosphere, background field", s, r, e, 0);
  // The surface (edges ~0.16) is coarser than 2 h on the x < 0 side: report the share only on
  // edges, assert a bound that this field reaches.
  EXPECT_GE(e.share(), 0.9);
  std::vector<int> sign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
  EXPECT_EQ(checkRefined(s, h, before, sign), "");
}

TEST(InteriorRefinement, DeterministicBudgetAndAbort)
{
  auto run = [](int maxPoints,
               std::vector<double>& points,
               std::vector<std::int32_t>& tets,
               std::vector<std::int32_t>& regions,
               std::vector<double>& h,
               const std::function<bool(double)>& progress = {})
  {
    Case s;
    s.surface = tt::cube(6);
    EXPECT_TRUE(prepare(s));
    const auto before = regionVolumes(s.mesh);
    h.assign(static_cast<std::size_t>(s.surface.pointCount()), 1.0 / 12);
    RefinementOptions options;
    options.maxPoints = maxPoints;
    RefinementResult r = refineInterior(s.mesh, h, options, {}, progress);
    extractRegionMesh(s.mesh, points, tets, regions);
    std::vector<int> sign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
    EXPECT_EQ(checkRefined(s, h, before, sign), "");
    return r;
  };
  std::vector<double> p1, p2, h1, h2;
  std::vector<std::int32_t> t1, t2, r1, r2;
  RefinementResult a = run(-1, p1, t1, r1, h1);
  RefinementResult b = run(-1, p2, t2, r2, h2);
  ASSERT_TRUE(a.ok && b.ok);
  EXPECT_GT(a.insertedPoints, 100);
  EXPECT_EQ(p1, p2);
  EXPECT_EQ(t1, t2);
  EXPECT_EQ(r1, r2);
  EXPECT_EQ(h1, h2);

  RefinementResult c = run(100, p2, t2, r2, h2);
  EXPECT_TRUE(c.ok);
  EXPECT_TRUE(c.budgetReached);
  EXPECT_EQ(c.insertedPoints, 100);

  // Abort at the first progress call (after 1024 points; the whole run inserts ~1900).
  int calls = 0;
  RefinementResult d =
    run(-1, p2, t2, r2, h2, [&calls](double f) { return f >= 0 && f <= 1 && ++calls < 1; });
  EXPECT_FALSE(d.ok);
  EXPECT_NE(d.error.find("abort"), std::string::npos);
  EXPECT_LT(d.insertedPoints, a.insertedPoints);
}

TEST(InteriorRefinement, SpeedUnitCubeH003)
{
  // h = 1/33 ~ 0.03 on a unit cube whose surface has the same spacing: ~400k tets. Timing is
  // printed, never asserted. Validity: exact orientation of every tet, region array in step.
  Case s;
  s.surface = tt::cube(33);
  ASSERT_TRUE(prepare(s));
  std::vector<double> h(static_cast<std::size_t>(s.surface.pointCount()), 1.0 / 33);
  const std::clock_t cpu0 = std::clock();
  RefinementResult r = refineInterior(s.mesh, h, RefinementOptions{});
  const double cpu = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  ASSERT_TRUE(r.ok) << r.error;
  std::printf("[cube h=1/33] refinement: %.3f s wall, %.3f s CPU (%.0f tets per CPU second)\n",
    r.seconds,
    cpu,
    s.mesh.mesh.liveTetCount() / std::max(cpu, 1e-9));
  const EdgeStats e = edgeStats(s.mesh, h);
  const double fcc = std::sqrt(2.0) * 33 * 33 * 33 - s.surface.pointCount() / 2.0;
  report("cube h=1/33", s, r, e, kDensity * fcc);
  EXPECT_GE(e.share(), 0.95);
  EXPECT_NEAR((s.mesh.mesh.vertexCount() - s.surface.pointCount()) / (kDensity * fcc), 1.0, 0.2);
  // The lattice fills the inside: few poor tets are left for the optimiser (3.2% below Q 0.3
  // with edge splitting alone, 0.3% with the lattice).
  EXPECT_GT(r.latticePoints, r.insertedPoints / 2);
  EXPECT_LT(shareBelow03(s.mesh), 0.01);
  const TetMesh& m = s.mesh.mesh;
  int bad = 0;
  for (TetId t = 0; t < m.tetCapacity(); ++t)
    if (!m.isDeleted(t))
      bad += predicates::orient3d(m.point(m.vertex(t, 0)),
               m.point(m.vertex(t, 1)),
               m.point(m.vertex(t, 2)),
               m.point(m.vertex(t, 3))) <= 0 ||
        s.mesh.region[t] != 0;
  EXPECT_EQ(bad, 0);
}

TEST(InteriorRefinement, TorusAndNestedSpheres)
{
  // Non-convex (torus) and nested shells (two regions: a ball inside a spherical shell), with
  // the default sizes: mean boundary edge length at each vertex.
  for (int which = 0; which < 2; ++which)
  {
    Case s;
    std::vector<int> sign;
    if (which == 0)
    {
      s.surface = tt::torus(1, 0.35, 40, 16);
      sign.assign(static_cast<std::size_t>(s.surface.triangleCount()), 1);
    }
    else
    {
      s.surface = tt::icosphere(3, 1.0);
      const std::int32_t outer = s.surface.triangleCount();
      s.surface.append(tt::icosphere(2, 0.5));
      sign.assign(static_cast<std::size_t>(s.surface.triangleCount()), 0);
      std::fill(sign.begin(), sign.begin() + outer, 1);
    }
    ASSERT_TRUE(prepare(s));
    ASSERT_EQ(s.boundary.regionCount, which == 0 ? 1 : 2);
    const auto before = regionVolumes(s.mesh);
    std::vector<double> h = boundaryEdgeSizes(s.surface.points.data(),
      s.surface.pointCount(),
      s.surface.triangles.data(),
      s.surface.triangleCount());
    RefinementResult r = refineInterior(s.mesh, h, RefinementOptions{});
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_GT(r.insertedPoints, 0);
    const EdgeStats e = edgeStats(s.mesh, h);
    const double estimate = kDensity * fccInteriorEstimate(s.mesh, h, s.surface.pointCount());
    report(which == 0 ? "torus" : "nested spheres", s, r, e, estimate);
    EXPECT_GE(e.share(), 0.95);
    EXPECT_NEAR((s.mesh.mesh.vertexCount() - s.surface.pointCount()) / estimate, 1.0, 0.2);
    EXPECT_EQ(checkRefined(s, h, before, sign), "");
  }
}

TEST(InteriorRefinement, ChecksRejectCorruptedResults)
{
  // The measures of this file must be able to fail: corrupt a good result in several ways.
  Case good;
  good.surface = tt::cube(6);
  ASSERT_TRUE(prepare(good));
  const auto before = regionVolumes(good.mesh);
  std::vector<double> h(static_cast<std::size_t>(good.surface.pointCount()), 1.0 / 6);
  ASSERT_TRUE(refineInterior(good.mesh, h, RefinementOptions{}).ok);
  std::vector<int> sign(static_cast<std::size_t>(good.surface.triangleCount()), 1);
  ASSERT_EQ(checkRefined(good, h, before, sign), "");
  ASSERT_GE(edgeStats(good.mesh, h).share(), 0.95);
  const VertexId firstNew = good.surface.pointCount();
  ASSERT_GT(good.mesh.mesh.vertexCount(), firstNew);
  TetId some = 0;
  while (good.mesh.mesh.isDeleted(some))
    ++some;

  // Sizes measured against another h: the band share collapses.
  std::vector<double> half = h;
  for (double& x : half)
    x *= 0.5;
  EXPECT_LT(edgeStats(good.mesh, half).share(), 0.5);
  // A missing size.
  std::vector<double> shorter(h.begin(), h.end() - 1);
  EXPECT_NE(checkRefined(good, shorter, before, sign), "");
  // An inverted tet.
  Case c1 = good;
  std::swap(c1.mesh.mesh.tets[4 * some], c1.mesh.mesh.tets[4 * some + 1]);
  EXPECT_NE(checkRefined(c1, h, before, sign), "");
  // A tet moved to another region (volumes per region change, interface appears).
  Case c2 = good;
  c2.mesh.region[some] = 1;
  EXPECT_NE(checkRefined(c2, h, before, sign), "");
  // A new vertex moved onto the boundary face z = 0 (inside a triangle).
  Case c3 = good;
  double* p = &c3.mesh.mesh.coords[3 * static_cast<std::size_t>(firstNew)];
  p[0] = 0.5 + 1.0 / 24;
  p[1] = 0.5 + 1.0 / 48;
  p[2] = 0;
  EXPECT_NE(checkRefined(c3, h, before, sign), "");
  // A boundary triangle lost (its tet deleted).
  Case c4 = good;
  for (TetId t = 0; t < c4.mesh.mesh.tetCapacity(); ++t)
    if (!c4.mesh.mesh.isDeleted(t) && c4.mesh.mesh.neighbor(t, 0) == kNoNeighbor)
    {
      c4.mesh.mesh.deleteTet(t);
      break;
    }
  EXPECT_NE(checkRefined(c4, h, before, sign), "");
  // The gradation measure sees a jump.
  std::vector<double> jump = h;
  jump[static_cast<std::size_t>(firstNew)] *= 10;
  EXPECT_GT(gradationExcess(good.mesh.mesh, jump, 1.5), 1.0);
}
